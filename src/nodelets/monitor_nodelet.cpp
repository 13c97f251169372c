// The monitor as a nodelet (README "In-process input"): the same MonitorNode as monitor_node,
// constructed on the nodelet's node handles, so that a driver loaded into the same manager hands
// it JointState without serialisation. MonitorNode subscribes with JointState::ConstPtr
// (boost::shared_ptr<const JointState>): a publisher in the same process that publishes a
// shared pointer delivers that very message, with no copy.
//
// The node handles are the single-threaded ones on purpose: MonitorNode's state (the merger, the
// stop policy, the Monitor's per-cycle data) is touched by its subscriptions, timers and services
// without locks, as in monitor_node's ros::spin(). The nodelet's ST queue runs its callbacks one
// at a time on the manager's worker threads; the multi-threaded handles would run them
// concurrently.
//
// ~direct_input (default true) puts DirectInputQueue over the ST queue: a JointState published
// in this process runs its cycle at once inside the driver's publish(), instead of waiting for
// the manager to wake its manager thread and then a worker thread (two thread wake-ups, which
// cost far more than the cycle itself); every other callback still goes through the ST queue.
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include <boost/make_shared.hpp>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/callback_queue_interface.h>
#include <ros/poll_manager.h>
#include <ros/subscription_queue.h>

#include "arm_collision_monitor/ros/monitor_node.h"

namespace arm_collision_monitor {
namespace {

// The DirectInputQueue whose callback this thread is running (nullptr: none). A callback that
// led back to its own queue (a publish into its own input) must not run nested in itself.
thread_local const void* t_running_queue = nullptr;

class RunningScope {
 public:
  explicit RunningScope(const void* queue) : previous_(t_running_queue) {
    t_running_queue = queue;
  }
  ~RunningScope() { t_running_queue = previous_; }
  RunningScope(const RunningScope&) = delete;
  RunningScope& operator=(const RunningScope&) = delete;

 private:
  const void* previous_;
};

// A callback of the underlying queue that holds the node's mutex while it runs. It keeps the
// mutex alive by itself: the underlying queue may run it after the DirectInputQueue is gone.
class SerialisedCallback : public ros::CallbackInterface {
 public:
  SerialisedCallback(ros::CallbackInterfacePtr callback, std::shared_ptr<std::mutex> mutex,
                     const void* queue)
      : callback_(std::move(callback)), mutex_(std::move(mutex)), queue_(queue) {}

  CallResult call() override {
    std::lock_guard<std::mutex> lock(*mutex_);
    const RunningScope scope(queue_);
    return callback_->call();
  }
  bool ready() override { return callback_->ready(); }

 private:
  ros::CallbackInterfacePtr callback_;
  std::shared_ptr<std::mutex> mutex_;
  const void* queue_;
};

// The monitor's callback queue: runs a message callback at once in the thread that delivers the
// message when that is provably safe, and hands every other callback to the nodelet's ST queue.
// One mutex serialises both kinds, so MonitorNode still sees one callback at a time.
//
// Why a delivering thread can deadlock, and which ones cannot. roscpp's TopicManager::publish()
// holds the process-wide advertised_topics_mutex_ for the whole publish, and an in-process
// subscriber's addCallback() runs inside it (Publication::publish -> IntraProcessSubscriberLink
// -> Subscription::handleMessage, which holds the subscription's callbacks_mutex_ too). The
// monitor's cycle publishes, which takes advertised_topics_mutex_ again. Hence two rules:
//  1. Never wait for the node's mutex in addCallback(): a timer or service callback of the node
//     holds it while it publishes (waiting for advertised_topics_mutex_), so a publishing thread
//     that waited for it would deadlock (the first version of this queue, reverted, locked here
//     and hung about one run in two). try_lock; when busy, the message goes to the ST queue
//     (SubscriptionQueue is a FIFO of messages: whichever call comes first takes the oldest, so
//     the order is kept).
//  2. Run inline only in a thread that already holds advertised_topics_mutex_, i.e. inside a
//     publish(): there the cycle's own publishes re-enter a mutex the thread holds, and nothing
//     it waits for can be held by a thread waiting for it. roscpp delivers messages in three
//     kinds of thread: publishing threads (in-process nocopy delivery, inside publish()); its
//     poll thread (TCP and UDP input, and serialised in-process delivery), which does not hold
//     advertised_topics_mutex_ but does hold the input subscription's callbacks_mutex_, so a
//     cycle there would wait for the former while a publisher of the same topic holds it and
//     waits for the latter (Subscription::getPublishTypes or handleMessage: seen in gdb with
//     TCP and in-process input on one topic); and a thread calling subscribe() or advertise(),
//     which delivers a latched message to a new link (for this node: only its own subscribe()
//     calls, before Arm()). The poll thread is recognised by its id, which a poll thread
//     listener records; until it has, and until Arm(), nothing runs inline.
//  Other queues that run callbacks inline in the delivering thread must keep these rules too:
//  the cycle waits for in-process subscribers' callbacks_mutex_ when it publishes.
class DirectInputQueue : public ros::CallbackQueueInterface {
 public:
  /// `queue` (the nodelet's ST queue) runs every callback that does not run inline.
  explicit DirectInputQueue(ros::CallbackQueueInterface* queue)
      : queue_(queue), mutex_(std::make_shared<std::mutex>()) {
    poll_listener_ = ros::PollManager::instance()->addPollThreadListener([this] {
      if (!is_poll_thread_known_.load(std::memory_order_relaxed)) {
        poll_thread_ = std::this_thread::get_id();
        is_poll_thread_known_.store(true, std::memory_order_release);
      }
    });
  }

  ~DirectInputQueue() override {
    // Returns once a running call of the listener is over (it holds the poll manager's lock).
    ros::PollManager::instance()->removePollThreadListener(poll_listener_);
  }

  DirectInputQueue(const DirectInputQueue&) = delete;
  DirectInputQueue& operator=(const DirectInputQueue&) = delete;

  /// From now on messages may run inline (call it once the node on this queue is built).
  void Arm() {
    const std::lock_guard<std::mutex> lock(*mutex_);
    is_armed_ = true;
  }

  /// No message runs inline after this returns (call it before the node on this queue goes):
  /// a running inline callback is over, and later ones go to the ST queue.
  void Disarm() {
    const std::lock_guard<std::mutex> lock(*mutex_);
    is_armed_ = false;
  }

  void addCallback(const ros::CallbackInterfacePtr& callback, std::uint64_t owner_id) override {
    if (t_running_queue != this && IsPublishingThread() &&
        dynamic_cast<ros::SubscriptionQueue*>(callback.get()) != nullptr) {
      std::unique_lock<std::mutex> lock(*mutex_, std::try_to_lock);
      if (lock.owns_lock() && is_armed_ && callback->ready()) {
        const RunningScope scope(this);
        if (callback->call() != ros::CallbackInterface::TryAgain) {
          return;
        }
      }
    }
    queue_->addCallback(boost::make_shared<SerialisedCallback>(callback, mutex_, this), owner_id);
  }

  void removeByID(std::uint64_t owner_id) override { queue_->removeByID(owner_id); }

 private:
  // Rule 2 above: not the poll thread (and not before its id is known).
  bool IsPublishingThread() const {
    return is_poll_thread_known_.load(std::memory_order_acquire) &&
           std::this_thread::get_id() != poll_thread_;
  }

  ros::CallbackQueueInterface* queue_;
  // Serialises the node's callbacks; shared with the callbacks handed to queue_.
  std::shared_ptr<std::mutex> mutex_;
  bool is_armed_ = false;  ///< guarded by *mutex_
  std::atomic<bool> is_poll_thread_known_{false};
  std::thread::id poll_thread_;  ///< written once, before is_poll_thread_known_
  boost::signals2::connection poll_listener_;
};

}  // namespace

class MonitorNodelet : public nodelet::Nodelet {
 public:
  ~MonitorNodelet() override {
    if (direct_queue_) {
      direct_queue_->Disarm();
    }
  }

 private:
  void onInit() override {
    ros::NodeHandle nh = getNodeHandle();
    ros::NodeHandle private_nh = getPrivateNodeHandle();
    if (private_nh.param("direct_input", true)) {
      direct_queue_ = std::make_unique<DirectInputQueue>(nh.getCallbackQueue());
      nh.setCallbackQueue(direct_queue_.get());
      private_nh.setCallbackQueue(direct_queue_.get());
    }
    try {
      node_ = std::make_unique<MonitorNode>(nh, private_nh);
    } catch (const std::exception& e) {
      // Start-up errors (LoadError names the file or parameter). Rethrown: the manager then
      // refuses the load, `nodelet load` fails, and a required launch node ends the launch.
      NODELET_FATAL("arm_collision_monitor: cannot start: %s", e.what());
      throw;
    }
    if (direct_queue_) {
      direct_queue_->Arm();
    }
  }

  std::unique_ptr<DirectInputQueue> direct_queue_;  // declared first: outlives node_
  std::unique_ptr<MonitorNode> node_;
};

}  // namespace arm_collision_monitor

PLUGINLIB_EXPORT_CLASS(arm_collision_monitor::MonitorNodelet, nodelet::Nodelet)
