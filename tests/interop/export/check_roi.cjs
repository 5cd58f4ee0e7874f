#!/usr/bin/env node
// Points of interest in cinepath's MAVLink 2 stream, decoded by node-mavlink: exactly one
// DO_SET_ROI_LOCATION (195) whose decoded x/y (degE7) and z are the expected point within a tolerance,
// in frame 3 (relative) or 0 (AMSL), followed later by exactly one DO_SET_ROI_NONE (197) in frame 2;
// no DO_GIMBAL_MANAGER_PITCHYAW (1000) or CONDITION_YAW (115) while it is active (the firmware points
// the camera then). With "none" instead of a point: no ROI item at all.
// Usage: check_roi.cjs <mission.mavlink> <lat_deg> <lon_deg> <alt_m> <tolerance_m>
//        check_roi.cjs <mission.mavlink> none
'use strict'
const { createReadStream } = require('node:fs')
const { createMavLinkStream, common, minimal } = require('node-mavlink')

const [binPath, ...rest] = process.argv.slice(2)
const expectNone = rest[0] === 'none'
const [lat, lon, alt, tol] = rest.map(Number)
const REGISTRY = { ...minimal.REGISTRY, ...common.REGISTRY }
const items = []
const stream = createMavLinkStream(createReadStream(binPath))
stream.on('data', (p) => {
  if (p.header.msgid === common.MissionItemInt.MSG_ID) items.push(p.protocol.data(p.payload, REGISTRY[p.header.msgid]))
})
stream.on('end', () => {
  const errors = []
  const rois = items.filter((d) => d.command === common.MavCmd.DO_SET_ROI_LOCATION)
  const nones = items.filter((d) => d.command === common.MavCmd.DO_SET_ROI_NONE)
  if (common.MavCmd.DO_SET_ROI_LOCATION !== 195 || common.MavCmd.DO_SET_ROI_NONE !== 197) errors.push('MavCmd ids')
  if (items.length < 2) errors.push(`only ${items.length} MISSION_ITEM_INT decoded`)
  if (expectNone) {
    if (rois.length || nones.length) errors.push(`${rois.length} ROI / ${nones.length} ROI_NONE items, expected none`)
  } else {
    if (rois.length !== 1) errors.push(`${rois.length} DO_SET_ROI_LOCATION items, expected 1`)
    if (nones.length !== 1) errors.push(`${nones.length} DO_SET_ROI_NONE items, expected 1`)
    if (rois.length === 1 && nones.length === 1) {
      const r = rois[0]
      const n = nones[0]
      if (![0, 3].includes(r.frame)) errors.push(`ROI frame ${r.frame}`)
      if (n.frame !== 2) errors.push(`ROI_NONE frame ${n.frame}`)
      if (!(n.seq > r.seq)) errors.push(`ROI_NONE (seq ${n.seq}) not after ROI (seq ${r.seq})`)
      for (const k of ['param1', 'param2', 'param3', 'param4']) if (r[k] !== 0) errors.push(`ROI ${k} = ${r[k]}`)
      // Metres on the ground from the decoded degE7 integers.
      const north = (r.x / 1e7 - lat) * 111320
      const east = (r.y / 1e7 - lon) * 111320 * Math.cos(lat * Math.PI / 180)
      const up = r.z - alt
      const miss = Math.hypot(north, east, up)
      if (!(miss <= tol)) errors.push(`ROI at ${r.x / 1e7}, ${r.y / 1e7}, ${r.z}: ${miss.toFixed(3)} m from the expected point`)
      for (const d of items) {
        if (d.seq > r.seq && d.seq < n.seq && (d.command === 1000 || d.command === 115)) {
          errors.push(`item seq ${d.seq}: command ${d.command} while the ROI is active`)
        }
      }
      if (!errors.length) console.log(`ROI ${miss.toFixed(3)} m from the expected point (seq ${r.seq}), ROI_NONE at seq ${n.seq}`)
    }
  }
  if (errors.length) {
    for (const e of errors) console.error('FAIL ' + e)
    process.exit(1)
  }
  console.log(`OK: ${items.length} items decoded by node-mavlink; ROI items as expected`)
})
