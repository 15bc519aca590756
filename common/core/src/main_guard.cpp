#include "twinslam/core/main_guard.hpp"

#include <exception>
#include <iostream>

#include "twinslam/core/error.hpp"

namespace twinslam {

int guarded_main(const std::string& program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return kExitBadInput;
  } catch (const UsageError& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << program << ": internal error: " << e.what() << '\n';
    return kExitInternal;
  }
}

}  // namespace twinslam
