// What `cinepath plan` warns about in a shot list it can plan but a crew would not mean: a moving actor
// whose last key is mid-stride stops dead there (before its first key and after its last an actor holds
// still, docs/plan.md). A shot that follows it past that key has its camera's path ease into the stop
// (Actor::EaseCameraIntoTheStop), but the aim, on the actor itself, stops dead with it.
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

}  // namespace cinepath::shots
