#include "registration_wait.hpp"

namespace twinslam::estimator {

RegistrationWait::Update RegistrationWait::observe(unsigned long long timed_out_total,
                                                   unsigned long long registrations_total) {
  Update u;
  if (registrations_total != registrations_seen_) {
    registrations_seen_ = registrations_total;
    in_a_row_ = 0;  // the registration answers (again)
  }
  if (timed_out_total > timed_out_seen_) {
    u.timed_out = timed_out_total - timed_out_seen_;
    timed_out_seen_ = timed_out_total;
    const bool was_waiting = in_a_row_ < give_up_after_;
    in_a_row_ += u.timed_out;
    u.gave_up = was_waiting && in_a_row_ >= give_up_after_;
  }
  return u;
}

}  // namespace twinslam::estimator
