#include "arm_collision_monitor/ros/inline_input_queue.h"

#include <boost/make_shared.hpp>
#include <ros/subscription_queue.h>

namespace arm_collision_monitor {
namespace {

// A callback of the underlying queue that takes the inline callbacks' mutex while it runs.
class SerialisedCallback : public ros::CallbackInterface {
 public:
  SerialisedCallback(ros::CallbackInterfacePtr callback,
                     std::shared_ptr<std::recursive_mutex> mutex)
      : callback_(std::move(callback)), mutex_(std::move(mutex)) {}

  CallResult call() override {
    std::lock_guard<std::recursive_mutex> lock(*mutex_);
    return callback_->call();
  }
  bool ready() override { return callback_->ready(); }

 private:
  ros::CallbackInterfacePtr callback_;
  std::shared_ptr<std::recursive_mutex> mutex_;
};

}  // namespace

InlineInputQueue::InlineInputQueue(ros::CallbackQueueInterface* queue)
    : queue_(queue), mutex_(std::make_shared<std::recursive_mutex>()) {}

void InlineInputQueue::addCallback(const ros::CallbackInterfacePtr& callback,
                                   std::uint64_t owner_id) {
  if (dynamic_cast<ros::SubscriptionQueue*>(callback.get()) != nullptr && callback->ready()) {
    std::lock_guard<std::recursive_mutex> lock(*mutex_);
    if (callback->call() != ros::CallbackInterface::TryAgain) {
      return;
    }
  }
  queue_->addCallback(boost::make_shared<SerialisedCallback>(callback, mutex_), owner_id);
}

void InlineInputQueue::removeByID(std::uint64_t owner_id) { queue_->removeByID(owner_id); }

}  // namespace arm_collision_monitor
