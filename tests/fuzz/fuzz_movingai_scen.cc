// libFuzzer target: MovingAI .scen scenario files, then the check against a
// 64 x 64 grid (as carribot does with the map the file names).
#include "fuzz/fuzz_input_file.h"
#include "workloads/carribot/movingai_scenario_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rc::fuzz::WriteInputFile("grid.map.scen", rc::fuzz::AsText(data, size));
  static const rc::OccupancyGrid grid(64, 64, 1.0);
  rc::fuzz::ExpectParsedOrInputError([&] {
    const rc::MovingAiScenarioFile file = rc::ReadMovingAiScenarios(path);
    for (const rc::MovingAiScenario& s : file.scenarios)
      rc::fuzz::Require(s.start_x >= 0 && s.start_y >= 0 && s.goal_x >= 0 && s.goal_y >= 0 && s.start_x < s.map_width &&
                            s.goal_x < s.map_width && s.start_y < s.map_height && s.goal_y < s.map_height,
                        "a start or goal lies outside the declared map");
    rc::CheckScenariosMatchMap(file, grid);
  });
  return 0;
}
