#!/usr/bin/env node
// Decodes cinepath's MAVLink 2 mission stream with node-mavlink (which checks every CRC and drops bad
// frames) and compares every field of every MISSION_ITEM_INT with what the .plan of the same export
// says was meant. Usage: check_mavlink.cjs <mission.mavlink> <mission.plan> <px4|ardupilot>
'use strict'
const { createReadStream, readFileSync } = require('node:fs')
const { createMavLinkStream, common, minimal } = require('node-mavlink')

const [binPath, planPath, firmware] = process.argv.slice(2)
const plan = JSON.parse(readFileSync(planPath, 'utf8'))
const meant = []
if (firmware === 'ardupilot') {
  const [lat, lon, alt] = plan.mission.plannedHomePosition
  meant.push({ command: 16, frame: 0, params: [0, 0, 0, 0, lat, lon, alt] })
}
for (const item of plan.mission.items) meant.push({ command: item.command, frame: item.frame, params: item.params })

const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY }
const f32 = (v) => Math.fround(v)
const failures = []
const fail = (msg) => { failures.push(msg); if (failures.length < 20) console.error('FAIL ' + msg) }
const packets = []
const stream = createMavLinkStream(createReadStream(binPath))
stream.on('data', (packet) => packets.push(packet))
stream.on('end', () => {
  if (packets.length !== meant.length + 1) fail(`decoded ${packets.length} valid frames, expected ${meant.length + 1}`)
  packets.forEach((p, i) => {
    if (p.header.magic !== 0xfd) fail(`frame ${i}: not MAVLink 2`)
    if (p.header.seq !== (i & 0xff)) fail(`frame ${i}: packet seq ${p.header.seq}`)
    if (p.header.sysid !== 255 || p.header.compid !== 190) fail(`frame ${i}: sender ${p.header.sysid}/${p.header.compid}`)
  })
  const first = packets[0]
  if (!first || first.header.msgid !== common.MissionCount.MSG_ID) fail('first frame is not MISSION_COUNT')
  else {
    const count = first.protocol.data(first.payload, REGISTRY[first.header.msgid])
    if (count.count !== meant.length) fail(`MISSION_COUNT.count ${count.count}, expected ${meant.length}`)
    if (count.targetSystem !== 1 || count.targetComponent !== 1) fail('MISSION_COUNT target')
  }
  packets.slice(1).forEach((p, seq) => {
    if (p.header.msgid !== common.MissionItemInt.MSG_ID) return fail(`frame ${seq + 1}: msgid ${p.header.msgid}`)
    const d = p.protocol.data(p.payload, REGISTRY[p.header.msgid])
    const m = meant[seq]
    if (!m) return
    const where = `item seq ${seq} (cmd ${m.command})`
    if (d.seq !== seq) fail(`${where}: seq ${d.seq}`)
    if (d.command !== m.command) fail(`${where}: command ${d.command}`)
    if (d.frame !== m.frame) fail(`${where}: frame ${d.frame}`)
    if (d.current !== 0) fail(`${where}: current ${d.current}`)
    if (d.autocontinue !== 1) fail(`${where}: autocontinue ${d.autocontinue}`)
    if (d.targetSystem !== 1 || d.targetComponent !== 1) fail(`${where}: target`)
    if ((d.missionType ?? 0) !== 0) fail(`${where}: mission type ${d.missionType}`)
    for (let k = 0; k < 4; k++) {
      const want = m.params[k] === null ? NaN : f32(m.params[k])
      const got = d[`param${k + 1}`]
      if (!(Object.is(got, want) || (Number.isNaN(got) && Number.isNaN(want)) || got === want)) {
        fail(`${where}: param${k + 1} ${got}, meant ${want}`)
      }
    }
    const global = m.frame === 0 || m.frame === 3
    const wantX = global ? Math.round(m.params[4] * 1e7) : Math.round(m.params[4])
    const wantY = global ? Math.round(m.params[5] * 1e7) : Math.round(m.params[5])
    if (d.x !== wantX) fail(`${where}: x ${d.x}, meant ${wantX}`)
    if (d.y !== wantY) fail(`${where}: y ${d.y}, meant ${wantY}`)
    if (d.z !== f32(m.params[6])) fail(`${where}: z ${d.z}, meant ${f32(m.params[6])}`)
  })
  if (failures.length) {
    console.error(`${failures.length} mismatches`)
    process.exit(1)
  }
  console.log(`OK: ${packets.length} frames decoded by node-mavlink, every field as meant`)
})
