#include "export/qgc_wpl.h"

#include "core/number_format.h"

namespace cinepath::exporter {

namespace {

void AppendRow(std::string& out, int seq, bool current, const MavItem& item) {
  out += std::to_string(seq) + '\t' + (current ? "1" : "0") + '\t' + std::to_string(item.frame) + '\t' +
         std::to_string(item.command);
  for (int p = 0; p < 6; ++p) out += '\t' + FormatFixed(item.params[p], 8);
  out += '\t' + FormatFixed(item.params[6], 6);
  out += '\t';
  out += item.autocontinue ? '1' : '0';
  out += '\n';
}

}  // namespace

std::string WriteQgcWpl(const Mission& mission, const MavMission& items) {
  std::string out = "QGC WPL 110\n";
  AppendRow(out, 0, true, HomeItem(mission));
  int seq = 1;
  for (const MavItem& item : items.items) AppendRow(out, seq++, false, item);
  return out;
}

}  // namespace cinepath::exporter
