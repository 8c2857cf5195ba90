#!/usr/bin/python3
"""Writes the reference values of rotord's tracking tests (tests/unit/tracking_*_test.cpp).

Run with Debian's python3-skyfield 1.45, python3-sgp4 2.15 and python3-ephem 4.1.4
(apt-get install python3-skyfield python3-ephem); the tests read the CSVs it
writes and never need Python. Deterministic: fixed TLEs, places and times.

  satellites.csv  per point: the look angles by the same chain rotord uses
                  (python-sgp4 TEME -> GMST IAU-82 with UT1 = UTC, no polar
                  motion -> WGS-84 observer -> east/north/up), computed here
                  independently, and by skyfield's full model (TEME -> ITRS
                  with its UT1 table).
  sun_moon.csv    topocentric apparent az/el of the Sun and the Moon from
                  PyEphem (pressure 0: no refraction).
  passes.csv      passes above a minimum elevation: the ISS and a Molniya from skyfield's
                  find_events (rise, culminate, set), each time refined by
                  bisection / golden section on skyfield's elevation, the Sun and the Moon from
                  PyEphem (centre of the disc, no refraction).
  places.csv      Maidenhead centres and great-circle bearings/distances on a
                  sphere of 6371.0088 km, by vector algebra (rotord uses
                  spherical trigonometry).
"""
import math
import os
from datetime import datetime, timedelta, timezone

import ephem
from sgp4.api import Satrec, jday
from skyfield.api import EarthSatellite, load, wgs84

HERE = os.path.dirname(os.path.abspath(__file__))

# Names must match tests/unit/tracking_geometry_test.cpp.
TLES = {
    # ISS, the example of python-sgp4's README.
    'ISS': ('1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991',
            '2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482'),
    # MOLNIYA 2-14 and XM-3 from the Vallado verification set (deep space).
    'MOLNIYA': ('1 08195U 75081A   06176.33215444  .00000099  00000-0  11873-3 0   813',
                '2 08195  64.1586 279.0717 6877146 264.7651  20.2257  2.00491383225656'),
    'XM3': ('1 28626U 05008A   06176.46683397 -.00000205  00000-0  10000-3 0  2190',
            '2 28626   0.0019 286.9433 0000335  13.7918  55.6504  1.00270176  4891'),
}
OBSERVERS = [  # lat, lon, alt_m
    (40.015, -105.27, 1655.0),
    (51.5074, -0.1278, 20.0),
    (-33.8688, 151.2093, 58.0),
    (69.6492, 18.9553, 100.0),
    (0.0, 0.0, 0.0),
]

WGS84_A = 6378.137
WGS84_F = 1 / 298.257223563
OMEGA = 7.292115146706979e-5


def gmst_iau82(jd_ut1):
    t = (jd_ut1 - 2451545.0) / 36525.0
    s = -6.2e-6 * t**3 + 0.093104 * t**2 + (876600.0 * 3600 + 8640184.812866) * t + 67310.54841
    return math.fmod(math.radians(s / 240.0), 2 * math.pi) % (2 * math.pi)


def observer_ecef(lat, lon, alt_m):
    e2 = WGS84_F * (2 - WGS84_F)
    phi, lam = math.radians(lat), math.radians(lon)
    n = WGS84_A / math.sqrt(1 - e2 * math.sin(phi) ** 2)
    h = alt_m / 1000
    return ((n + h) * math.cos(phi) * math.cos(lam), (n + h) * math.cos(phi) * math.sin(lam),
            (n * (1 - e2) + h) * math.sin(phi))


def simple_look(sat, when, lat, lon, alt_m):
    jd, fr = jday(when.year, when.month, when.day, when.hour, when.minute,
                  when.second + when.microsecond * 1e-6)
    err, r, v = sat.sgp4(jd, fr)
    assert err == 0, err
    g = gmst_iau82(jd + fr)
    c, s = math.cos(g), math.sin(g)
    rp = (c * r[0] + s * r[1], -s * r[0] + c * r[1], r[2])
    vp = (c * v[0] + s * v[1] + OMEGA * rp[1], -s * v[0] + c * v[1] - OMEGA * rp[0], v[2])
    o = observer_ecef(lat, lon, alt_m)
    rho = [rp[i] - o[i] for i in range(3)]
    phi, lam = math.radians(lat), math.radians(lon)
    east = (-math.sin(lam), math.cos(lam), 0.0)
    north = (-math.sin(phi) * math.cos(lam), -math.sin(phi) * math.sin(lam), math.cos(phi))
    up = (math.cos(phi) * math.cos(lam), math.cos(phi) * math.sin(lam), math.sin(phi))
    dot = lambda a, b: sum(x * y for x, y in zip(a, b))
    e, n, u = dot(rho, east), dot(rho, north), dot(rho, up)
    rng = math.sqrt(e * e + n * n + u * u)
    az = math.degrees(math.atan2(e, n)) % 360.0
    el = math.degrees(math.asin(u / rng))
    rr = dot(rho, vp) / rng
    return az, el, rng, rr


def satellites():
    ts = load.timescale(builtin=True)
    rows = []
    plans = {
        'ISS': (datetime(2019, 12, 9, 12, 0, tzinfo=timezone.utc), 24 * 60, 1),
        'MOLNIYA': (datetime(2006, 6, 25, 8, 0, tzinfo=timezone.utc), 24 * 60, 60),
        'XM3': (datetime(2006, 6, 25, 12, 0, tzinfo=timezone.utc), 24 * 60, 180),
    }
    for name, (l1, l2) in TLES.items():
        sat = Satrec.twoline2rv(l1, l2)
        sky = EarthSatellite(l1, l2, name, ts)
        start, minutes, step = plans[name]
        for oi, (lat, lon, alt) in enumerate(OBSERVERS):
            topos = wgs84.latlon(lat, lon, elevation_m=alt)
            for k in range(0, minutes, step):
                when = start + timedelta(minutes=k, seconds=7 * oi)
                az, el, rng, rr = simple_look(sat, when, lat, lon, alt)
                # ISS: every point above -5 deg, and one point in 30 below it.
                if name == 'ISS' and el < -5 and k % 30:
                    continue
                t = ts.from_datetime(when)
                alt_sf, az_sf, dist_sf = (sky - topos).at(t).altaz()
                rows.append((name, when.strftime('%Y-%m-%dT%H:%M:%SZ'), lat, lon, alt, az, el, rng,
                             rr, az_sf.degrees, alt_sf.degrees, dist_sf.km))
    with open(os.path.join(HERE, 'satellites.csv'), 'w') as f:
        f.write('name,utc,lat_deg,lon_deg,alt_m,az_simple_deg,el_simple_deg,range_simple_km,'
                'range_rate_simple_km_s,az_skyfield_deg,el_skyfield_deg,range_skyfield_km\n')
        for r in rows:
            f.write('%s,%s,%.4f,%.4f,%.1f,%.6f,%.6f,%.5f,%.7f,%.6f,%.6f,%.5f\n' % r)
    return len(rows)


def sun_moon():
    rows = []
    start = datetime(2019, 1, 1, 0, 0, tzinfo=timezone.utc)
    for k in range(400):
        # Spread over 2019-2031 and over the day (steps coprime to a day).
        when = start + timedelta(hours=k * 283 + (k * 37) % 60 / 60.0)
        lat, lon, alt = OBSERVERS[k % len(OBSERVERS)]
        obs = ephem.Observer()
        obs.lat, obs.lon, obs.elevation = str(lat), str(lon), alt
        obs.pressure = 0  # no refraction
        obs.date = ephem.Date(when.replace(tzinfo=None))
        for name, body in (('sun', ephem.Sun()), ('moon', ephem.Moon())):
            body.compute(obs)
            rows.append((name, when.strftime('%Y-%m-%dT%H:%M:%SZ'), lat, lon, alt,
                         math.degrees(body.az), math.degrees(body.alt)))
    with open(os.path.join(HERE, 'sun_moon.csv'), 'w') as f:
        f.write('body,utc,lat_deg,lon_deg,alt_m,az_deg,el_deg\n')
        for r in rows:
            f.write('%s,%s,%.4f,%.4f,%.1f,%.6f,%.6f\n' % r)
    return len(rows)


def refine_crossing(sky, topos, ts, t, min_el, rising, bracket_s=60):
    """find_events' times can be seconds off over a long window: bisect to 1 ms."""
    el = lambda d: (sky - topos).at(ts.from_datetime(d)).altaz()[0].degrees - min_el
    d = t.utc_datetime()
    lo, hi = d - timedelta(seconds=bracket_s), d + timedelta(seconds=bracket_s)
    assert (el(lo) < 0) == rising and (el(hi) < 0) != rising
    while hi - lo > timedelta(milliseconds=1):
        mid = lo + (hi - lo) / 2
        if (el(mid) < 0) == rising:
            lo = mid
        else:
            hi = mid
    return lo + (hi - lo) / 2


def refine_culmination(sky, topos, ts, t, bracket_s=60):
    el = lambda d: (sky - topos).at(ts.from_datetime(d)).altaz()[0].degrees
    d = t.utc_datetime()
    a, b = d - timedelta(seconds=bracket_s), d + timedelta(seconds=bracket_s)
    g = (math.sqrt(5) - 1) / 2
    while b - a > timedelta(milliseconds=1):
        c, e = b - (b - a) * g, a + (b - a) * g
        if el(c) > el(e):
            b = e
        else:
            a = c
    m = a + (b - a) / 2
    return m, el(m)


def passes():
    ts = load.timescale(builtin=True)
    rows = []
    plans = [
        # name, window start, days, observers, minimum elevations, refinement bracket (s)
        ('ISS', datetime(2019, 12, 9, 12, 0, tzinfo=timezone.utc), 1, OBSERVERS[:4], (0.0, 10.0), 60),
        ('MOLNIYA', datetime(2006, 6, 25, 8, 0, tzinfo=timezone.utc), 1,
         [OBSERVERS[0], OBSERVERS[1], OBSERVERS[3]], (10.0,), 600),
    ]
    for name, t0, days, observers, min_els, bracket in plans:
        l1, l2 = TLES[name]
        sky = EarthSatellite(l1, l2, name, ts)
        t1 = t0 + timedelta(days=days)
        for lat, lon, alt in observers:
            topos = wgs84.latlon(lat, lon, elevation_m=alt)
            for min_el in min_els:
                times, events = sky.find_events(topos, ts.from_datetime(t0), ts.from_datetime(t1),
                                                altitude_degrees=min_el)
                current = {}
                for t, e in zip(times, events):
                    if e == 0:
                        current = {'aos': t}
                    elif e == 1 and 'aos' in current:
                        current['max'] = t
                    elif e == 2 and 'max' in current:
                        culmination, alt_deg = refine_culmination(sky, topos, ts, current['max'],
                                                                  bracket)
                        rows.append((name, lat, lon, alt, min_el, t0, t1,
                                     refine_crossing(sky, topos, ts, current['aos'], min_el, True,
                                                     bracket),
                                     refine_crossing(sky, topos, ts, t, min_el, False, bracket),
                                     culmination, alt_deg))
                        current = {}
    # Sun and Moon: rising to setting of the disc's centre, no refraction.
    s0 = datetime(2024, 3, 20, 0, 0, tzinfo=timezone.utc)
    s1 = s0 + timedelta(days=2)
    for lat, lon, alt in OBSERVERS[:3]:
        for name, body in (('sun', ephem.Sun()), ('moon', ephem.Moon())):
            obs = ephem.Observer()
            obs.lat, obs.lon, obs.elevation = str(lat), str(lon), alt
            obs.pressure = 0
            obs.horizon = '0'
            obs.date = ephem.Date(s0.replace(tzinfo=None))
            while True:
                rise = obs.next_rising(body, use_center=True)
                if rise.datetime() > s1.replace(tzinfo=None):
                    break
                obs.date = rise
                transit = obs.next_transit(body)
                setting = obs.next_setting(body, use_center=True)
                if setting.datetime() > s1.replace(tzinfo=None):
                    break
                obs.date = transit
                body.compute(obs)
                rows.append((name, lat, lon, alt, 0.0, s0, s1,
                             rise.datetime().replace(tzinfo=timezone.utc),
                             setting.datetime().replace(tzinfo=timezone.utc),
                             transit.datetime().replace(tzinfo=timezone.utc),
                             math.degrees(body.alt)))
                obs.date = setting + ephem.minute
    fmt = lambda d: d.strftime('%Y-%m-%dT%H:%M:%S.') + '%03dZ' % (d.microsecond // 1000)
    with open(os.path.join(HERE, 'passes.csv'), 'w') as f:
        f.write('target,lat_deg,lon_deg,alt_m,min_el_deg,from_utc,to_utc,aos_utc,los_utc,'
                'max_el_utc,max_el_deg\n')
        for r in rows:
            f.write('%s,%.4f,%.4f,%.1f,%.1f,%s,%s,%s,%s,%s,%.5f\n' % (
                r[0], r[1], r[2], r[3], r[4], fmt(r[5]), fmt(r[6]), fmt(r[7]), fmt(r[8]),
                fmt(r[9]), r[10]))
    return len(rows)


def locator_centre(loc):
    loc = loc.upper()
    lon, lat = -180.0, -90.0
    w_lon, w_lat = 20.0, 10.0
    for i in range(0, len(loc), 2):
        pair = i // 2
        if pair % 2 == 0:
            base, div = 'A', (18 if pair == 0 else 24)
            x, y = ord(loc[i]) - ord('A'), ord(loc[i + 1]) - ord('A')
        else:
            base, div = '0', 10
            x, y = int(loc[i]), int(loc[i + 1])
        if pair > 0:
            w_lon /= div
            w_lat /= div
        lon += x * w_lon
        lat += y * w_lat
    return lat + w_lat / 2, lon + w_lon / 2


def great_circle(lat1, lon1, lat2, lon2, radius=6371.0088):
    def unit(lat, lon):
        p, l = math.radians(lat), math.radians(lon)
        return (math.cos(p) * math.cos(l), math.cos(p) * math.sin(l), math.sin(p))
    a, b = unit(lat1, lon1), unit(lat2, lon2)
    dot = sum(x * y for x, y in zip(a, b))
    cross = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    dist = radius * math.atan2(math.sqrt(sum(c * c for c in cross)), dot)
    p, l = math.radians(lat1), math.radians(lon1)
    north = (-math.sin(p) * math.cos(l), -math.sin(p) * math.sin(l), math.cos(p))
    east = (-math.sin(l), math.cos(l), 0.0)
    d = [b[i] - dot * a[i] for i in range(3)]
    bearing = math.degrees(math.atan2(sum(x * y for x, y in zip(d, east)),
                                      sum(x * y for x, y in zip(d, north)))) % 360.0
    return bearing, dist


def places():
    stations = [(52.0, 5.0), (40.015, -105.27), (-33.8688, 151.2093), (69.6492, 18.9553)]
    targets = ['JO22', 'FN31pr', 'PM95vq', 'KP03xa', 'IO91wm42', 'RE78ir', 'BL11bh16oo',
               'GG87jc', 'AA00aa', 'RR99xx99xx', 'JN58td', 'OL72bb']
    rows = []
    for slat, slon in stations:
        for loc in targets:
            lat, lon = locator_centre(loc)
            bearing, dist = great_circle(slat, slon, lat, lon)
            rows.append((slat, slon, loc, lat, lon, bearing, dist))
    with open(os.path.join(HERE, 'places.csv'), 'w') as f:
        f.write('station_lat_deg,station_lon_deg,locator,lat_deg,lon_deg,bearing_deg,distance_km\n')
        for r in rows:
            f.write('%.4f,%.4f,%s,%.9f,%.9f,%.6f,%.4f\n' % r)
    return len(rows)


if __name__ == '__main__':
    print('satellites.csv', satellites())
    print('sun_moon.csv', sun_moon())
    print('places.csv', places())
    print('passes.csv', passes())
