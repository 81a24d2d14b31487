#pragma once

// Per-thread scratch state reused across calls of a function that runs once a frame: a gaze
// loop or a dataset renders thousands of 400 x 400 frames, and fresh full-frame images each
// frame cost a page fault per 4 KB page (in the ASan tree an mmap and an munmap as well).
// The caller must overwrite whatever it reads, so a call's result never depends on the calls
// before it.
namespace fovea::gaze {

// Holds the calling thread's T for its lifetime, or a fresh T if the thread's is already held
// (the function entered again on the same thread before it returned, e.g. from a task that TBB
// lets a waiting thread run).
template <class T>
class ThreadScratch {
 public:
  ThreadScratch() : slot_(threadSlot().held ? &own_ : &threadSlot()) { slot_->held = true; }
  ~ThreadScratch() { slot_->held = false; }
  ThreadScratch(const ThreadScratch&) = delete;
  ThreadScratch& operator=(const ThreadScratch&) = delete;
  T& operator*() const { return slot_->value; }
  T* operator->() const { return &slot_->value; }

 private:
  struct Slot {
    T value{};
    bool held = false;
  };
  static Slot& threadSlot() {
    thread_local Slot slot;
    return slot;
  }
  Slot own_;
  Slot* slot_;
};

}  // namespace fovea::gaze
