#!/usr/bin/env python3
"""Checks Home Assistant MQTT discovery messages (lines 'topic payload', as
`mosquitto_sub -v` prints them) against tests/data/mqtt/ha_discovery.schema.json,
a schema written from Home Assistant's MQTT discovery documentation (Home
Assistant is not packaged here). Also checks what Home Assistant relies on
across messages: unique_id unique, one device, topics that exist.
Usage: ha_discovery_check.py SCHEMA MESSAGES_FILE PREFIX; prints problems, exit 1 if any."""
import json
import re
import sys

import jsonschema


def component_schema(doc, component):
    schema = json.loads(json.dumps(doc["components"][component]))
    props = schema["properties"]
    del props["$common"]
    props.update(doc["$defs"]["common"])
    schema["$defs"] = doc["$defs"]
    return schema


def main():
    doc = json.load(open(sys.argv[1]))
    lines = [l for l in open(sys.argv[2]).read().splitlines() if l.strip()]
    prefix = sys.argv[3]
    problems = []
    seen_ids = set()
    devices = set()
    entities = set()
    for line in lines:
        topic, _, payload = line.partition(" ")
        m = re.match(doc["topic_pattern"], topic)
        if not m:
            problems.append(f"{topic}: not a discovery topic")
            continue
        component = m.group(1)
        if payload == "":
            continue  # an empty retained config removes an entity
        try:
            config = json.loads(payload)
        except ValueError as e:
            problems.append(f"{topic}: not JSON: {e}")
            continue
        try:
            jsonschema.validate(config, component_schema(doc, component))
        except jsonschema.ValidationError as e:
            problems.append(f"{topic}: {e.message} at {list(e.absolute_path)}")
            continue
        if config["unique_id"] in seen_ids:
            problems.append(f"{topic}: unique_id {config['unique_id']} used twice")
        seen_ids.add(config["unique_id"])
        ident = config["device"]["identifiers"]
        devices.add(json.dumps(ident))
        for key in ("state_topic", "availability_topic", "command_topic"):
            if key in config and not config[key].startswith(prefix + "/"):
                problems.append(f"{topic}: {key} {config[key]} is not under {prefix}/")
        if "command_topic" in config and "/cmd/" not in config["command_topic"]:
            problems.append(f"{topic}: command_topic is not a rotord command")
        entities.add(component + "/" + topic.split("/")[-2])
    if len(devices) != 1:
        problems.append(f"expected one device, got {len(devices)}")
    for needed in ("sensor/azimuth", "number/target_azimuth", "button/stop", "button/park",
                   "binary_sensor/fault"):
        if needed not in entities:
            problems.append(f"missing entity {needed}")
    for p in problems:
        print(p)
    print(f"{len(lines)} messages, {len(entities)} entities, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
