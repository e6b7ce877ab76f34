// The example's physical and numerical parameters, with the defaults the tests and the docs use.
#pragma once

struct HeatParameters {
  unsigned int initial_refinement = 3;  // global refinements of the unit cube: 8^3 cells
  unsigned int source_refinement = 2;   // extra levels around the source before the first step
  unsigned int max_level = 5;           // no cell finer than 1/32
  unsigned int refine_every = 3;        // steps between two adaptations; 0 keeps the first mesh
  unsigned int steps = 24;
  double dt = 0.005;
  double source_width = 0.08;  // the Gaussian's standard deviation
};
