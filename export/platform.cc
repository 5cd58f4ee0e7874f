#include "export/platform.h"

#include "core/error.h"

namespace cinepath::exporter {

const char* FirmwareName(Firmware firmware) { return firmware == Firmware::kPx4 ? "px4" : "ardupilot"; }

Firmware ParseFirmware(const std::string& name) {
  if (name == "px4") return Firmware::kPx4;
  if (name == "ardupilot") return Firmware::kArduPilot;
  throw InputError("firmware: unknown firmware '" + name + "' (known: px4, ardupilot)");
}

}  // namespace cinepath::exporter
