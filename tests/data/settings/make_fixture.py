# Drives main's daemon to change every settable key from its default, one POST
# per key, and reports which keys it could not change.
import json, sys, urllib.request
port = int(sys.argv[1])
base = f'http://127.0.0.1:{port}'
def get(path):
    return json.load(urllib.request.urlopen(base + path))
def post(doc):
    req = urllib.request.Request(base + '/api/settings', data=json.dumps(doc).encode(),
                                 headers={'Content-Type': 'application/json'}, method='POST')
    try:
        with urllib.request.urlopen(req) as r: return r.status, r.read().decode()
    except urllib.error.HTTPError as e: return e.code, e.read().decode()
schema = get('/api/settings/schema')['settings']
rows = {r['key']: r for r in schema}
# Hand-picked first: rows with rules across settings.
first = [
  {"az.min_deg": -15.5, "az.max_deg": 455.25},
  {"el.min_deg": -2.5, "el.max_deg": 178.75},
  {"az.pot_cal_lo_counts": 101.5, "az.pot_cal_lo_deg": -14.5, "az.pot_cal_hi_counts": 3701.25, "az.pot_cal_hi_deg": 451.5,
   "az.pot_cal_m1_counts": 601, "az.pot_cal_m1_deg": 50.5, "az.pot_cal_m2_counts": 1102, "az.pot_cal_m2_deg": 111.25,
   "az.pot_cal_m3_counts": 1603, "az.pot_cal_m3_deg": 172, "az.pot_cal_m4_counts": 2104, "az.pot_cal_m4_deg": 233.75,
   "az.pot_cal_m5_counts": 2605, "az.pot_cal_m5_deg": 294.5, "az.pot_cal_m6_counts": 3106, "az.pot_cal_m6_deg": 355.25,
   "az.pot_cal_mid_points": 6},
  {"el.pot_cal_lo_counts": 3650.5, "el.pot_cal_lo_deg": -1.5, "el.pot_cal_hi_counts": 120.25, "el.pot_cal_hi_deg": 177.5,
   "el.pot_cal_m1_counts": 3100, "el.pot_cal_m1_deg": 20.5, "el.pot_cal_m2_counts": 2600, "el.pot_cal_m2_deg": 45.25,
   "el.pot_cal_m3_counts": 2100, "el.pot_cal_m3_deg": 70, "el.pot_cal_m4_counts": 1600, "el.pot_cal_m4_deg": 95.75,
   "el.pot_cal_m5_counts": 1100, "el.pot_cal_m5_deg": 120.5, "el.pot_cal_m6_counts": 600, "el.pot_cal_m6_deg": 150.25,
   "el.pot_cal_mid_points": 5},
  {"az.pwm_slow_duty": 0.41, "az.pwm_fast_duty": 0.93, "el.pwm_slow_duty": 0.52, "el.pwm_fast_duty": 0.88},
  {"park.az_deg": 12.5, "park.el_deg": 7.25, "wind.stow_az_deg": 33.5},
  {"mag.x_min": -1234, "mag.x_max": 1111, "mag.y_min": -987, "mag.y_max": 1321},
]
texts = {
  "wind.mqtt_topic": "weather/wind_speed", "wind.mqtt_dir_topic": "weather/wind_dir",
  "n1mm.rotor_name": "Tower 2", "wifi.ssid": "Shack Wi-Fi", "wifi.password": "wpa2-secret-1",
  "wifi.ap_password": "setup-secret-2", "net.hostname": "rotor-east", "net.ipv4_address": "192.168.7.20",
  "net.ipv4_netmask": "255.255.254.0", "net.ipv4_gateway": "192.168.7.1", "net.ipv4_dns": "192.168.7.2",
  "time.sntp_server": "ntp.example.org", "web.allowed_hosts": "rotor.example.org, proxy.lan",
  "access.control_networks": "127.0.0.1, ::1, 192.168.7.0/24", "mqtt.host": "127.0.0.1",
  "mqtt.tls_ca": "/etc/rotord/ca.pem", "mqtt.client_id": "rotord-fixture", "mqtt.user": "rotor",
  "mqtt.password": "broker-secret", "mqtt.prefix": "station/rotor", "track.tle_url": "http://127.0.0.1:9/tle.txt",
}
for n in range(1, 17): texts[f"preset.{n}"] = f"{(n * 21) % 360}{'L' if n % 5 == 0 else ''}:P{n}"
special_numbers = {"mqtt.port": 9, "n1mm.port": 40412, "pst.port": 40012, "n1mm.report_port": 40413}
log = []
for doc in first:
    st, body = post(doc); log.append((list(doc)[0], st, body[:200]))
for k, v in special_numbers.items():
    st, body = post({k: v}); log.append((k, st, body[:200]))
for k, v in texts.items():
    st, body = post({k: v}); log.append((k, st, body[:200]))
done = set()
for d in first: done |= set(d)
done |= set(texts) | set(special_numbers)
def candidates(i, r):
    t = r['type']; lo, hi, d = r['min'], r['max'], r['default']
    if t == 'bool': return [not d]
    if t == 'enum':
        return [c for c in r['choices'] if c != d][::-1]
    out = []
    for k in range(1, 40):
        for sign in (1, -1):
            if t == 'int': v = d + sign * (k + i % 11)
            else: v = round(d + sign * (0.01 * (i % 37 + 1) + 0.125 * (k - 1)), 4)
            if lo <= v <= hi and v != d: out.append(v)
    return out
stubborn = []
for i, r in enumerate(schema):
    k = r['key']
    if k in done or r.get('hidden') or k == 'el.enabled': continue
    ok = False
    for v in candidates(i, r)[:40]:
        st, body = post({k: v})
        if st == 200: ok = True; break
        last = body[:160]
    if not ok: stubborn.append((k, last))
# el.enabled last: off on the az/el g5500 profile.
log.append(('el.enabled', *post({"el.enabled": False})))
for l in log:
    if l[1] != 200: print('REFUSED', l)
for s in stubborn: print('STUBBORN', s)
