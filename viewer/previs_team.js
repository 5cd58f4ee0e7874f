
// ---- several drones (docs/view.md, "Several drones") ----
// Appended to viewer/previs.js for a plan of several drones, in the same module: the page above is drawn
// about one flight (data.team.primary); this shows every flight over it, each in its colour (the palette of
// `cinepath plan --plot`): its path, its camera frustum and position at the current time, its home. A
// selector in the HUD picks the drone the camera view looks through, or "edit": the drone live in the edit
// at that time (before the first cut, the first cut's drone). The timeline shows the edit's cuts (bars in
// the live drone's colour above the track) and the team's conflicts (separation red, a drone in another's
// shot orange). Every flight is sampled on one clock: sample k is at k / frame rate; a flight that has
// ended holds its last sample.
const team = data.team;
const teamStyle = document.createElement('style');
teamStyle.textContent = `
  #track .edit { position: absolute; top: -7px; height: 5px; border-left: 1px solid #000; box-sizing: border-box; }
  #track .conflict { position: absolute; top: 14px; height: 22px; }
  #drones { display: flex; flex-wrap: wrap; gap: 4px; align-items: center; margin-top: 4px; }
  #drones .chip { display: inline-block; width: 10px; height: 10px; margin-right: 4px; border: 1px solid #0008; }`;
document.head.appendChild(teamStyle);
current.visible = false;  // the primary flight is drawn below in its colour, like the others

function teamFrustumPoints(f, j, out) {
  return cameraFrustumPoints(f.pos(j), f.quat(j), f.vertical_fov_deg[j], f.aspect, f.focus_distance_m[j], out);
}

let teamPaths = 0;
const flights = team.flights.map((f) => {
  const n = f.time_s.length;
  f.pos = (j) => new THREE.Vector3(f.position_m[3 * j], f.position_m[3 * j + 1], f.position_m[3 * j + 2]);
  f.quat = (j) => new THREE.Quaternion(f.quaternion[4 * j], f.quaternion[4 * j + 1], f.quaternion[4 * j + 2],
                                       f.quaternion[4 * j + 3]);
  const color = new THREE.Color(f.colour);
  // The path, broken at the flight's own cuts.
  const cuts = new Set(f.cuts_before_sample);
  const p = [];
  for (let j = 0; j + 1 < n; ++j) {
    if (cuts.has(j + 1)) continue;
    p.push(...f.pos(j).toArray(), ...f.pos(j + 1).toArray());
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(p, 3));
  const path = overlay(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color })));
  path.name = `flight ${f.name}`;
  if (n > 1) ++teamPaths;
  const frustum = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color }));
  const marker = new THREE.Mesh(new THREE.SphereGeometry(unit * 1.5, 16, 12), new THREE.MeshBasicMaterial({ color }));
  const tag = label(f.name, 0.026, f.colour);
  tag.center.set(0.5, -0.6);
  marker.add(tag);
  const group = new THREE.Group();
  group.add(frustum);
  group.add(marker);
  overlay(group);
  if (f.home_m) {
    const home = new THREE.Mesh(new THREE.BoxGeometry(unit * 2, unit * 0.6, unit * 2),
                                new THREE.MeshBasicMaterial({ color }));
    home.position.set(...f.home_m);
    overlay(home);
  }
  return { f, n, frustum, marker };
});
const flightIndex = (name) => team.flights.findIndex((f) => f.name === name);

// Which flight is live in the edit at time t, or -1 without an edit.
function liveFlightAt(t) {
  if (!team.edit.length) return -1;
  let live = flightIndex(team.edit[0].drone);
  for (const cut of team.edit) if (cut.at_s <= t + 1e-9) live = flightIndex(cut.drone);
  return live;
}

// The drone selector: "edit" (when there is one) and every drone by name, with its colour.
let selected = team.edit.length ? 'edit' : team.primary;
{
  const box = document.createElement('div');
  box.id = 'drones';
  box.className = 'line';
  box.appendChild(document.createTextNode('camera view: '));
  const buttons = [];
  const add = (value, text, colour) => {
    const b = document.createElement('button');
    b.dataset.drone = String(value);
    if (colour) {
      const chip = document.createElement('span');
      chip.className = 'chip';
      chip.style.background = colour;
      b.appendChild(chip);
    }
    b.appendChild(document.createTextNode(text));
    b.addEventListener('click', () => {
      selected = value;
      for (const other of buttons) other.classList.toggle('on', other === b);
      setSample(k);
    });
    b.classList.toggle('on', value === selected);
    buttons.push(b);
    box.appendChild(b);
  };
  if (team.edit.length) add('edit', 'edit (live drone)', null);
  team.flights.forEach((f, i) => add(i, f.name, f.colour));
  $('hud').appendChild(box);
  $('hud-plan').textContent += ` · ${team.flights.length} drones: ` +
    team.flights.map((f) => `${f.name} (${f.drone}, ${f.time_s.length} samples)`).join(', ');
  $('legend').style.display = 'none';  // the speed colours are not drawn for several drones
}

// The timeline: the edit's cuts and the team's conflicts.
{
  const track = $('track');
  for (let c = 0; c < team.edit.length; ++c) {
    const cut = team.edit[c];
    const end = c + 1 < team.edit.length ? team.edit[c + 1].at_s : t1;
    const d = document.createElement('div');
    d.className = 'edit';
    d.style.left = `${((cut.at_s - t0) / span) * 100}%`;
    d.style.width = `${Math.max(0.2, ((end - cut.at_s) / span) * 100)}%`;
    const i = flightIndex(cut.drone);
    d.style.background = i >= 0 ? team.flights[i].colour : '#888';
    d.title = `${fmt(cut.at_s, 2)} s: cut to ${cut.drone}${cut.match_focus ? ' (focus matched)' : ''}`;
    track.appendChild(d);
  }
  for (const v of team.conflicts) {
    const d = document.createElement('div');
    d.className = 'conflict';
    d.dataset.limit = v.limit;
    d.style.left = `${((v.start_time_s - t0) / span) * 100}%`;
    d.style.width = `${Math.max(0.2, ((v.end_time_s - v.start_time_s) / span) * 100)}%`;
    d.style.background = v.limit === 'separation' ? '#ff3b2f66' : '#ff9d2e66';
    d.title = v.limit === 'separation'
      ? `separation ${v.drone}–${v.other}: ${fmt(v.worst_value, 2)} m < ${fmt(v.limit_value, 2)} m, ` +
        `${fmt(v.start_time_s, 2)}–${fmt(v.end_time_s, 2)} s`
      : `${v.other} in ${v.drone}'s shot (${fmt(v.worst_value, 1)} px), ` +
        `${fmt(v.start_time_s, 2)}–${fmt(v.end_time_s, 2)} s`;
    track.insertBefore(d, slider);
  }
  const box = $('violations');
  const lines = team.conflicts.map((v) => (v.limit === 'separation'
    ? `✖ separation ${v.drone}–${v.other}: ${fmt(v.worst_value, 2)} < ${fmt(v.limit_value, 2)} m`
    : `✖ ${v.other} in ${v.drone}'s shot`) + ` at ${fmt(v.start_time_s, 2)}–${fmt(v.end_time_s, 2)} s`);
  box.textContent = (lines.length ? lines.join('\n') : `✔ team: every pair ≥ ${fmt(team.min_separation_m, 1)} m ` +
                     'apart, no drone in another\'s shot') + '\n' + box.textContent;
  box.style.color = lines.length ? '#ffb27a' : box.style.color;
}

// Every flight at sample k, and the camera view through the selected (or live) drone.
const primarySetSample = setSample;
setSample = function (index) {
  primarySetSample(index);
  if (N === 0) return;
  const t = S.time_s[k];
  for (const { f, n, frustum, marker } of flights) {
    const j = Math.min(k, n - 1);
    marker.position.copy(f.pos(j));
    frustum.geometry.dispose();
    frustum.geometry = new THREE.BufferGeometry();
    frustum.geometry.setAttribute('position', new THREE.Float32BufferAttribute(teamFrustumPoints(f, j, []), 3));
  }
  const live = liveFlightAt(t);
  const index_ = selected === 'edit' ? live : selected;
  const { f, n } = flights[index_ >= 0 ? index_ : team.primary];
  const j = Math.min(k, n - 1);
  shotCamera.position.copy(f.pos(j));
  shotCamera.quaternion.copy(f.quat(j));
  shotCamera.fov = f.vertical_fov_deg[j];
  shotCamera.aspect = f.aspect;
  shotCamera.updateProjectionMatrix();
  // Rendered frames (--frames) belong to one sequence: the edit's when the plan has one, else the primary's.
  const framesOf = team.edit.length ? selected === 'edit' : selected === team.primary;
  const img = $('frame-img');
  if (!framesOf) img.style.display = 'none';
  if (!framesOf || !frames[String(k)]) {
    $('camera-label').textContent = `${f.name}${selected === 'edit' ? ' (live in the edit)' : ''}` +
      `${j < k ? ', holding its last sample' : ''}`;
  }
  // The readout is the viewed drone's (the lens graphs stay the primary flight's).
  const p = f.pos(j), focus = f.focus_distance_m[j];
  const readout = $('readout');
  readout.dataset.drone = f.name;
  readout.dataset.e = fmt(p.x, 3);
  readout.dataset.n = fmt(-p.z, 3);
  readout.dataset.u = fmt(p.y, 3);
  readout.textContent =
    `t ${fmt(t, 3)} s   frame ${k} / ${N - 1}   drone ${f.name}` +
    `${live >= 0 ? '   live in the edit: ' + team.flights[live].name : ''}\n` +
    `camera  E ${fmt(p.x, 2)}  N ${fmt(-p.z, 2)}  U ${fmt(p.y, 2)} m${j < k ? '   (flight ended: holding)' : ''}\n` +
    `lens    focus ${fmt(focus, 2)} m (${fmt(dioptres(focus), 3)} dpt)  vFOV ${fmt(f.vertical_fov_deg[j], 1)}°` +
    `   (lens graphs: ${team.flights[team.primary].name})`;
  requestRender();
};
setSample(k);
document.body.dataset.flights = String(team.flights.length);
document.body.dataset.flightPaths = String(teamPaths);
document.body.dataset.editCuts = String(team.edit.length);
document.body.dataset.conflicts = String(team.conflicts.length);
document.body.dataset.errors = String(window.previsErrors.length);
document.body.dataset.state = window.previsErrors.length ? 'error' : 'ready';
