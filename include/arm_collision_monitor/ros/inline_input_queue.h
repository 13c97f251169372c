// A callback queue that runs message callbacks at once, in the thread that delivers the message
// (for a publisher in the same process: inside its publish(); for TCP: roscpp's network thread),
// and hands every other callback (timers, services) to an underlying queue. One mutex serialises
// both kinds, so the node on it still sees one callback at a time, as on a single-threaded queue.
//
// Used by the monitor nodelet (README "In-process input") so that a driver nodelet's publish()
// runs the cycle directly, without waking a queue's thread; the price is that publish() returns
// only after the cycle. Only message callbacks run inline on purpose: roscpp adds timer
// callbacks while holding its timer locks, which a callback run inline could need again.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>

#include <ros/callback_queue_interface.h>

namespace arm_collision_monitor {

class InlineInputQueue : public ros::CallbackQueueInterface {
 public:
  /// `queue` runs the callbacks that are not messages; it must outlive this queue's callbacks.
  explicit InlineInputQueue(ros::CallbackQueueInterface* queue);

  void addCallback(const ros::CallbackInterfacePtr& callback, std::uint64_t owner_id) override;
  void removeByID(std::uint64_t owner_id) override;

 private:
  ros::CallbackQueueInterface* queue_;
  // Recursive: a callback that publishes to a subscription of the same queue runs it inline.
  // Shared with the callbacks handed to queue_, which may outlive this object.
  std::shared_ptr<std::recursive_mutex> mutex_;
};

}  // namespace arm_collision_monitor
