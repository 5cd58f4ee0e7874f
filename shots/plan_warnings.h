// What `cinepath plan` warns about in a shot list it can plan but a crew would not mean: an actor placed
// at an absolute height far off the scene's ground; a moving actor whose last key is mid-stride stops dead
// there (before its first key and after its last an actor holds still, docs/plan.md). A shot that follows
// it past that key has its camera's path ease into the stop (Actor::EaseCameraIntoTheStop), but the aim,
// on the actor itself, stops dead with it.
#pragma once

#include <string>
#include <vector>

#include "core/team_plan.h"
#include "shots/shot_list.h"

namespace cinepath::shots {

// An actor arriving at its last key faster than this (m/s) stops dead there.
constexpr double kStopsDeadMS = 0.25;

// One line per shot (of any drone) whose subject stops dead at its last key inside the shot (more than a
// frame before the shot's end): the actor, the key's time, its speed there, the shot and its end, and what
// would fix it. In the order of the flights and their shots.
std::vector<std::string> StopsDeadWarnings(const ShotList& list, const TeamPlan& plan);

// An actor whose base the shot list placed at an absolute height more than this (m) above the scene's
// ground floats: most likely an [e, n, u] copied from a plan without a scene, where u = 0 is the origin's
// height, not the ground's.
constexpr double kFloatsAboveGroundM = 3.0;

// With the scene's mesh (list.ground): one line per actor, not kept on the ground, whose position or a key
// given at an absolute height stands more than kFloatsAboveGroundM above the mesh's highest surface under it,
// or with its head under the mesh's surface there (the key farthest off): the actor, the field, how far, and
// how to stand it on the ground. A positioned actor may be meant to fly or climb: a warning, not an error.
std::vector<std::string> FloatingActorWarnings(const ShotList& list);

}  // namespace cinepath::shots
