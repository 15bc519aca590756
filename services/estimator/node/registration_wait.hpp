#pragma once
// When a lockstep estimator (--await-registration) holds frames for the registration answering a LocalMap. Holding
// them makes a replay repeatable whatever the edge's speed; holding them for an edge that cannot answer only stalls
// the flight by registration_wait per keyframe (seen in CI: a secured run whose estimator and registration had not
// authenticated each other yet ran into its test's timeout). So: wait only while the registration is matched both
// ways, and after `give_up_after` waits in a row ran out, not at all until a registration arrives again. Free of DDS:
// the node passes what it counted.
namespace twinslam::estimator {

class RegistrationWait {
 public:
  // give_up_after >= 1 (the config validates it).
  explicit RegistrationWait(int give_up_after) : give_up_after_(static_cast<unsigned long long>(give_up_after)) {}

  struct Update {
    unsigned long long timed_out = 0;  // waits that ran out since the last update
    bool gave_up = false;              // this update reached give_up_after waits in a row
  };
  // Per frame: the waits that ran out and the registrations received so far (both running totals).
  Update observe(unsigned long long timed_out_total, unsigned long long registrations_total);
  // Whether the next LocalMap holds the frames: `link_up` when the registration hears LocalMaps and is heard.
  bool should_wait(bool link_up) const { return link_up && in_a_row_ < give_up_after_; }

 private:
  unsigned long long give_up_after_;
  unsigned long long timed_out_seen_ = 0, registrations_seen_ = 0;
  unsigned long long in_a_row_ = 0;  // waits run out since the last registration arrived
};

}  // namespace twinslam::estimator
