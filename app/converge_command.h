// `pathlab converge`: several configurations rendered for the same time (or sample count), their
// error against a reference recorded over time, an efficiency table and a log-log plot.
#pragma once

#include "app/shared_options.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace pathlab::app {

struct ConvergeOptions {
  SceneOptions scene;
  std::string outputDir;
  std::string reference;  // empty: render one (bpt, balance) and cache it in outputDir by hash
  std::string mask;       // an image: the error is measured where it is at least maskThreshold (empty: everywhere)
  double maskThreshold = 0.5;
  std::string configs = "bpt;pt;lt;bpt:mis=power;bpt:mis=uniform";
  SampleBudget budget;    // per configuration; neither given: 10 seconds
  double referenceSeconds = 0.0;  // default 10 x seconds
  int referenceSpp = 0;           // default 10 x spp
  double checkpointFactor = 1.5;
  std::string clock = "wall";  // or "cpu": process CPU time (fair on a loaded machine, with --threads 1)
  ImageSizeOptions size;  // not given: the reference's size, or 256 without --reference
  int maxLength = 10;
  bool russianRoulette = true;
  uint64_t seed = 0;
  int threads = 0;
  bool force = false;
};

class Job;

void addConvergeCommand(CLI::App& app, ConvergeOptions& options);
// Returns the process exit code. Errors are exceptions, reported by main. As one rank of `job`
// (app/job.h; one process: a plain Job): every configuration (and the reference) rendered by all
// ranks together, the results written by the leader.
int runConverge(ConvergeOptions options, Job& job);

}  // namespace pathlab::app
