#include "floorgrid/server/request_slots.hpp"

namespace floorgrid::server {

std::optional<RequestSlots::Slot> RequestSlots::try_take() {
  std::size_t taken = in_use_.load();
  do {
    if (taken >= slots_)
      return std::nullopt;
  } while (!in_use_.compare_exchange_weak(taken, taken + 1));
  return Slot(this);
}

}  // namespace floorgrid::server
