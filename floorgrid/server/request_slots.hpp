#pragma once

#include <atomic>
#include <cstddef>
#include <optional>

namespace floorgrid::server {

/// A count of requests allowed at once (the large ones, whose memory adds up): a request takes a
/// slot for as long as it is answered, or is told to come back when none is free.
class RequestSlots {
 public:
  /// One slot taken; given back when it dies.
  class Slot {
   public:
    Slot(Slot&& other) noexcept : owner_(other.owner_) { other.owner_ = nullptr; }
    Slot& operator=(Slot&& other) noexcept {
      if (this != &other) {
        release();
        owner_ = other.owner_;
        other.owner_ = nullptr;
      }
      return *this;
    }
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot() { release(); }

   private:
    void release() {
      if (owner_ != nullptr)
        owner_->in_use_.fetch_sub(1);
      owner_ = nullptr;
    }
    friend class RequestSlots;
    explicit Slot(RequestSlots* owner) : owner_(owner) {}
    RequestSlots* owner_;
  };

  /// `slots` at once (0: none, every request is refused).
  explicit RequestSlots(std::size_t slots) : slots_(slots) {}
  RequestSlots(const RequestSlots&) = delete;
  RequestSlots& operator=(const RequestSlots&) = delete;

  /// A slot, or none when all are taken.
  std::optional<Slot> try_take();
  /// Slots taken now.
  std::size_t in_use() const { return in_use_.load(); }
  /// Slots in all.
  std::size_t slots() const { return slots_; }

 private:
  std::size_t slots_;
  std::atomic<std::size_t> in_use_ = 0;
};

}  // namespace floorgrid::server
