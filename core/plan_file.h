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
#include "core/trajectory.h"

namespace cinepath {

inline constexpr const char* kPlanSchema = "cinepath.plan/1";

Json PlanToJson(const Trajectory& plan);
std::string PlanToText(const Trajectory& plan);  // DumpJson(PlanToJson(plan))

// Reads a plan document; InputError("<source>: <json path>: ...") on anything malformed.
Trajectory PlanFromJson(const Json& document, const std::string& source);
Trajectory ReadPlanFile(const std::filesystem::path& path);

// A shot's `hold` list (shots.json's "optimize" block, plan.json's intent): names out of
// kOptimizeChannels (core/trajectory.h); InputError naming the element for anything else.
std::vector<std::string> ReadHoldList(const JsonField& hold);

// The samples as CSV (one header line, one row per sample, comma separated, '.' decimals, focus
// "inf" at infinity, subjects joined by ';'). Columns: docs/plan-format.md.
std::string PlanSamplesToCsv(const Trajectory& plan);

}  // namespace cinepath
