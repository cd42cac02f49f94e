// Uses the installed headers under the needle/ prefix: loads a case, runs the dynamics at its
// rated speed and prints the largest lift in mm.
#include <cstdio>

#include "needle/apps/case/case_scene.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const needle::Case c = needle::LoadCase(argv[1]);
  const needle::Scene scene = needle::MakeScene(c);
  needle::SimulationOptions o = needle::OptionsFromCase(c);
  o.method = "dopri5";
  const needle::SimulationResult r = needle::Simulate(scene, c.engine.speed_rpm, o);
  std::printf("%s %.6f mm\n", needle::RunStatusName(r.status).c_str(), r.max_lift_m * 1e3);
  return 0;
}
