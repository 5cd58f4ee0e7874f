#!/usr/bin/env node
// QGC WPL 110 rules (docs/mission-formats.md §1): header, exactly 12 TAB-separated numeric fields per line, row 0 =
// home (current 1, frame 0, cmd 16), contiguous indices, current 0 elsewhere, no blank lines,
// dot decimals; and the rows match the .plan of the same export. Usage: check_wpl.cjs <wpl> <plan>
'use strict'
const { readFileSync } = require('node:fs')
const [wplPath, planPath] = process.argv.slice(2)
const text = readFileSync(wplPath, 'utf8')
const plan = JSON.parse(readFileSync(planPath, 'utf8'))
const errors = []
if (!text.endsWith('\n')) errors.push('no final newline')
const lines = text.slice(0, -1).split('\n')
if (lines[0] !== 'QGC WPL 110') errors.push(`header '${lines[0]}'`)
const rows = lines.slice(1)
rows.forEach((line, i) => {
  const f = line.split('\t')
  if (f.length !== 12) return errors.push(`line ${i + 2}: ${f.length} fields`)
  if (!f.every((x) => /^-?\d+(\.\d+)?$/.test(x))) errors.push(`line ${i + 2}: non-numeric field`)
  if (Number(f[0]) !== i) errors.push(`line ${i + 2}: index ${f[0]}`)
  if (i === 0 && (f[1] !== '1' || f[2] !== '0' || f[3] !== '16')) errors.push('row 0 is not the home row')
  if (i > 0 && f[1] !== '0') errors.push(`line ${i + 2}: current ${f[1]}`)
  if (f[11] !== '1') errors.push(`line ${i + 2}: autocontinue ${f[11]}`)
  if (i === 0) {
    const [lat, lon, alt] = plan.mission.plannedHomePosition
    if (Math.abs(Number(f[8]) - lat) > 5e-9 || Math.abs(Number(f[9]) - lon) > 5e-9 || Math.abs(Number(f[10]) - alt) > 5e-7) {
      errors.push('home row differs from plannedHomePosition')
    }
    return
  }
  const item = plan.mission.items[i - 1]
  if (!item) return errors.push(`line ${i + 2}: more rows than .plan items`)
  if (Number(f[3]) !== item.command || Number(f[2]) !== item.frame) errors.push(`line ${i + 2}: command/frame differ from .plan`)
  for (let k = 0; k < 7; k++) {
    const tol = k === 6 ? 5e-7 : 5e-9
    if (Math.abs(Number(f[4 + k]) - item.params[k]) > tol) errors.push(`line ${i + 2}: param${k + 1} ${f[4 + k]} vs ${item.params[k]}`)
  }
})
if (rows.length !== plan.mission.items.length + 1) errors.push(`${rows.length} rows, .plan has ${plan.mission.items.length} items + home`)
if (errors.length) {
  for (const e of errors.slice(0, 20)) console.error('FAIL ' + e)
  process.exit(1)
}
console.log(`OK: ${rows.length} rows, 12 TAB fields each, home first, same items as the .plan`)
