#pragma once

#include <string>

namespace kiosk::wall::test {

/** @brief A 2x2 wall of 64x36-pixel screens at 1 px/mm with 4 mm mullions. */
inline std::string wall2x2(const std::string& extra = "") {
    return R"({
  "grid": {"rows": 2, "columns": 2},
  "screenDefaults": {"pixels": [64, 36], "activeMm": [64, 36]},
  "mullionMm": [4, 4],
  "screens": [
    {"id": "tl", "row": 0, "column": 0}, {"id": "tr", "row": 0, "column": 1},
    {"id": "bl", "row": 1, "column": 0}, {"id": "br", "row": 1, "column": 1}
  ],
  "nodes": [{"id": "n1", "screens": ["tl"]}, {"id": "n2", "screens": ["tr"]},
            {"id": "n3", "screens": ["bl", "br"]}],
  "leader": "n1",
  "sync": {"state": "ipc:///tmp/kiosk-wall-test-state", "ready": "ipc:///tmp/kiosk-wall-test-ready"})" +
           extra + "\n}\n";
}

}  // namespace kiosk::wall::test
