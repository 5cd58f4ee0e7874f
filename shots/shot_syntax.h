// How one shot of a shot list is written (shots.json "shots[i]"): every shot type declares its keys
// once, in one table (kShotSyntax in shot_syntax.cc), with the function that reads them. Unknown keys
// are refused from that same declaration, so the keys a type accepts and the keys it reads cannot
// drift apart. Reference: docs/plan.md ("Shot types").
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "core/geodesy.h"
#include "core/json.h"
#include "shots/shot_list.h"

namespace cinepath::shots {

// The keys every shot takes, whatever its type.
const std::vector<std::string_view>& CommonShotKeys();
// The keys a type takes besides the common ones, in the order docs/plan.md lists them.
const std::vector<std::string_view>& ShotTypeKeys(ShotType type);

// Reads shots[index]. `shot_start_s` is the shot's start on the plan clock (look-ats at key times use
// the actors' positions then); `frame` converts lat/lon positions (null without an origin).
// InputError names the JSON path of the offending key.
ShotSpec ParseShotSpec(const JsonField& shot, size_t index, const ShotList& list, double shot_start_s,
                       const EnuFrame* frame);

}  // namespace cinepath::shots
