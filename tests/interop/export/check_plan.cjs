#!/usr/bin/env node
// Validates a .plan with ajv against docs/qgc-plan.schema.json and re-checks QGC's loading rules
// explicitly (docs/mission-formats.md §2): three top-level objects, 7 params, boolean autoContinue, the three
// altitude keys together, numeric Altitude/AltitudeMode, frames 0/2/3 only, DO items in frame 2.
// Usage: check_plan.cjs <schema.json> <mission.plan>
'use strict'
const { readFileSync } = require('node:fs')
const Ajv = require('ajv')

const [schemaPath, planPath] = process.argv.slice(2)
const schema = JSON.parse(readFileSync(schemaPath, 'utf8'))
const plan = JSON.parse(readFileSync(planPath, 'utf8'))
const ajv = new Ajv({ allErrors: true, strict: true })
const validate = ajv.compile(schema)
const errors = []
if (!validate(plan)) for (const e of validate.errors) errors.push(`schema: ${e.instancePath} ${e.message}`)

for (const key of ['mission', 'geoFence', 'rallyPoints']) {
  if (typeof plan[key] !== 'object' || plan[key] === null || Array.isArray(plan[key])) errors.push(`${key} missing`)
}
const nav = new Set([16, 22])
const positional = new Set([16, 22, 195])  // DO_SET_ROI_LOCATION carries a location: global frame
plan.mission.items.forEach((item, i) => {
  const where = `items[${i}]`
  if (!Array.isArray(item.params) || item.params.length !== 7) errors.push(`${where}: params length`)
  if (typeof item.autoContinue !== 'boolean') errors.push(`${where}: autoContinue not boolean`)
  const altKeys = ['AltitudeMode', 'Altitude', 'AMSLAltAboveTerrain'].filter((k) => k in item).length
  if (altKeys !== 0 && altKeys !== 3) errors.push(`${where}: altitude keys not together`)
  if (altKeys === 3 && (typeof item.Altitude !== 'number' || typeof item.AltitudeMode !== 'number')) {
    errors.push(`${where}: Altitude/AltitudeMode not numeric`)
  }
  if (![0, 2, 3].includes(item.frame)) errors.push(`${where}: frame ${item.frame} (emit 0/2/3 only)`)
  if (!positional.has(item.command) && item.command !== 20 && item.frame !== 2) errors.push(`${where}: DO item not in frame 2`)
  if (item.command === 195 && ![0, 3].includes(item.frame)) errors.push(`${where}: DO_SET_ROI_LOCATION not in frame 0/3`)
  if (nav.has(item.command) && altKeys !== 3) errors.push(`${where}: NAV item without altitude keys`)
  if (altKeys === 3 && item.Altitude !== item.params[6]) errors.push(`${where}: Altitude != params[6]`)
  item.params.forEach((p, k) => { if (p === null) errors.push(`${where}: params[${k}] is null (NaN)`) })
  if (item.doJumpId !== i + 1) errors.push(`${where}: doJumpId ${item.doJumpId}`)
})
if (errors.length) {
  for (const e of errors.slice(0, 20)) console.error('FAIL ' + e)
  process.exit(1)
}
console.log(`OK: ${planPath} valid against the schema and QGC's loading rules (${plan.mission.items.length} items)`)
