// plan.json: the planned flight every later stage reads (optimize, render, export, info).
//
// Format reference: docs/plan-format.md. Versioned by "schema": "cinepath.plan/1"; a reader accepts
// any "cinepath.plan/1" file and refuses other versions with an InputError naming the key.
// Numbers are written with a documented precision (docs/plan-format.md, "Precision") so golden files
// are stable: positions, heights, focus 1e-6 m; angles 1e-6 deg; lat/lon 1e-9 deg; quaternions 1e-9;
// time 1e-9 s. Focus at infinity is null. Quaternions are [w, x, y, z] (Hamilton, unit norm;
// renormalized on reading).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/json.h"
#include "core/team_plan.h"
#include "core/trajectory.h"

namespace cinepath {

inline constexpr const char* kPlanSchema = "cinepath.plan/1";
// Several drones (core/team_plan.h): one flight per drone, the edit and the team report.
inline constexpr const char* kTeamPlanSchema = "cinepath.plan/2";

Json PlanToJson(const Trajectory& plan);
std::string PlanToText(const Trajectory& plan);  // DumpJson(PlanToJson(plan))

// Reads a plan document; InputError("<source>: <json path>: ...") on anything malformed.
Trajectory PlanFromJson(const Json& document, const std::string& source);
Trajectory ReadPlanFile(const std::filesystem::path& path);

// Either version as a team: a "cinepath.plan/1" file reads as one flight with `single` set (its drone
// named after its profile); TeamPlanToJson writes such a plan back as version 1, byte for byte.
TeamPlan TeamPlanFromJson(const Json& document, const std::string& source);
TeamPlan ReadTeamPlanFile(const std::filesystem::path& path);
// Every flight's Trajectory::notes, in order: what the reader took from elsewhere than the file.
std::vector<std::string> TeamPlanNotes(const TeamPlan& plan);
Json TeamPlanToJson(const TeamPlan& plan);
std::string TeamPlanToText(const TeamPlan& plan);

// A shot's `hold` list (shots.json's "optimize" block, plan.json's intent): names out of
// kOptimizeChannels (core/trajectory.h); InputError naming the element for anything else.
std::vector<std::string> ReadHoldList(const JsonField& hold);

// The samples as CSV (one header line, one row per sample, comma separated, '.' decimals, focus
// "inf" at infinity, subjects joined by ';'). Columns: docs/plan-format.md.
std::string PlanSamplesToCsv(const Trajectory& plan);
// The same for a team: a first column "drone" (the flight's name) before them, flights in order. A
// version 1 plan gives PlanSamplesToCsv's text.
std::string TeamPlanSamplesToCsv(const TeamPlan& plan);

}  // namespace cinepath
