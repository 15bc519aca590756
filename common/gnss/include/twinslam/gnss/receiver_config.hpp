#pragma once
// Configuration of the single-point receiver (receiver.hpp). YAML section `receiver:` of a config file, e.g.
//   receiver: {earth_rotation: true, false_alarm_probability: 0.001, max_exclusions: 3}
#include <string>

namespace twinslam::gnss {

struct ReceiverConfig {
  int max_iterations = 20;                   // Gauss-Newton iterations per solve
  double convergence_m = 1e-4;               // stop when the update is shorter [m]
  bool earth_rotation = true;                // Sagnac: turn satellite positions into the frame of reception time
  double elevation_mask_deg = 0;             // observations below are not used [deg]
  // Weak signals are often reflected ones (NLOS): below this C/N0 an observation's sigma grows by a factor
  // 10^((reference - C/N0) / 20), i.e. its variance by one decade per 10 dB-Hz. 0 turns it off [dB-Hz].
  double cn0_reference_dbhz = 45;
  double false_alarm_probability = 1e-3;     // of the chi-square residual test that triggers an exclusion [-]
  int max_exclusions = 3;                    // satellites excluded at most per epoch (fault detection and exclusion)
  double max_residual_m = 1e4;               // |residual| beyond this after convergence: the fix is refused [m]

  void validate(const std::string& file) const;  // InputError "FILE: receiver key 'K': ..." when out of range
};

// Reads a YAML file whose one top-level key is `receiver:` (another key is an error); keys not given keep their
// defaults. Validates.
ReceiverConfig load_receiver_config(const std::string& path);

}  // namespace twinslam::gnss
