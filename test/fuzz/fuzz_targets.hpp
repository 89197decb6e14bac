// The three fuzz targets of issue 11: one function each, shared by the libFuzzer entry files (fuzz_*.cpp) and the
// seed replay in the GoogleTest suite (fuzz_seeds_test.cpp). Each returns "" for an admissible outcome and a
// description of the broken invariant otherwise; the libFuzzer entries abort on it (require()).
//
// Every input is bounded: at most kMaxSimulatedTime of simulated time (the step target may ask up to 10 s) in at
// most kMaxSteps calls of advance_to with a 0 s budget (one step or event each; milliseconds, at most ~2 s under
// ASan for a stalled run).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace top_sim::fuzz {

constexpr double kMaxSimulatedTime = 1.0e-3;  // [s] simulated after a scene loads or a command is accepted
constexpr int kMaxSteps = 64;                 // advance_to(t, 0 s budget) calls per advance

// Bytes as a YAML scene: parse_scene either throws SceneError with a message, or returns a scene whose initial
// state is finite and that a Simulator runs for kMaxSimulatedTime to a finite state or a named fault.
std::string scene_loader(const std::uint8_t* data, std::size_t size);

// Bytes as 1-3 Commands (any doubles, any friction law and table, patch and air fields) for any shipped scene or a
// variant (bodies of shapes, patch, air, auto model): submit() says what validate() says; an accepted command is
// applied and the run ends finite or with a named fault; a rejected one has a message and changes nothing (the run
// equals a twin that never saw it).
std::string command(const std::uint8_t* data, std::size_t size);

// Bytes as an initial state (tilt, spin, velocities, gap, ...), integrator settings and the keys of bodies of shapes,
// patch, air and auto model (shapes, offsets, radii, patch radius and pressure, drilling law, rolling resistance,
// air drag, model kind, auto tolerance, materials, restitution, inertia, static friction) on one of the scenes: what
// the loader admits steps, one step at a time (at most kMaxSteps, over 1 ms to 10 s), to a finite state or a named
// fault.
std::string step(const std::uint8_t* data, std::size_t size);

// The config/scenes files (without .yaml) the command and step targets start from: every shipped scene.
std::vector<std::string> scene_files();

// Prints the broken invariant of `target` and aborts (the libFuzzer entries call this); does nothing for "".
void require(const char* target, const std::string& verdict);

}  // namespace top_sim::fuzz
