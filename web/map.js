// The map page: the map, the beam on it, the pick panel, turning to a place
// and the presets (places.js does the work).
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  const msg = $('msg');
  const updateMap = rotordPlaces.wireMap($('map'), msg);
  rotordPlaces.wirePlace(msg);
  rotordPlaces.wirePresets(msg);
  $('stop').addEventListener('click', async () => {
    const r = await rotord.post('/api/stop', {});
    rotord.message(msg, r.status === 200 ? 'stopped' : `error ${r.status}`, r.status === 200);
  });
  function show(s) {
    updateMap(s);
    $('beam-az').textContent = s.beam ? rotord.fmt(s.beam.az_deg) + '°' : '–';
    $('mech').textContent = `mechanism ${rotord.fmt(s.az.position_deg)}°` +
      (s.el ? `, el ${rotord.fmt(s.el.position_deg)}°` : '');
    $('tgt').textContent = s.beam && s.beam.target_az_deg !== null ? rotord.fmt(s.beam.target_az_deg) + '°' : '–';
  }
  rotordAccess.wire(msg);
  rotord.live((s) => { rotordAccess.update(s); show(s); });
})();
