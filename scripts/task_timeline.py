#!/usr/bin/python3
"""Plays a task bag into a running monitor node and prints a timeline of its warnings and a
summary (used by scripts/run).

Each message of the bag is published on its topic, restamped with the current time (so the
node's staleness checks see live input), after the node's report for the previous one arrived:
every message is processed and counted, and the order of the two arms' messages is the bag's.
With --rate R > 0 the messages are also paced at R times the recorded speed (for watching in
rviz); --rate 0 plays as fast as the node answers.

  task_timeline.py --bag task3.bag --title "task 3" [--grasp right_link7:front_box] [--rate 0]
"""
import argparse
import re
import sys
import threading
import time

import rosbag
import rospy
from sensor_msgs.msg import JointState

from arm_collision_monitor.msg import MonitorReport
from arm_collision_monitor.srv import SetGraspTarget

POLL_PERIOD_S = 0.005


class Reports(object):
    def __init__(self):
        self.lock = threading.Lock()
        self.reports = []

    def on_report(self, msg):
        with self.lock:
            self.reports.append(msg)

    def count(self):
        with self.lock:
            return len(self.reports)

    def wait_for(self, count, timeout_s):
        """Report number `count` (0-based), waiting at most timeout_s; None on timeout."""
        deadline = time.time() + timeout_s
        while not rospy.is_shutdown():
            with self.lock:
                if len(self.reports) > count:
                    return self.reports[count]
            if time.time() > deadline:
                return None
            time.sleep(POLL_PERIOD_S)
        return None


def wait_until(ready, timeout_s):
    deadline = time.time() + timeout_s
    while time.time() < deadline and not rospy.is_shutdown():
        if ready():
            return True
        time.sleep(0.02)
    return ready()


def percentile(sorted_values, p):
    """Nearest-rank percentile of an ascending list (p in (0, 100])."""
    if not sorted_values:
        return float('nan')
    rank = max(1, int(-(-p * len(sorted_values) // 100)))
    return sorted_values[min(rank, len(sorted_values)) - 1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--bag', required=True)
    parser.add_argument('--title', default='')
    parser.add_argument('--node', default='/arm_collision_monitor')
    parser.add_argument('--grasp', action='append', default=[], metavar='LINK:OBJECT')
    parser.add_argument('--rate', type=float, default=0.0)
    parser.add_argument('--timeout', type=float, default=10.0,
                        help='seconds to wait for each report and for the node at start-up')
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node('task_timeline', anonymous=True, disable_signals=True)
    title = args.title or args.bag

    reports = Reports()
    rospy.Subscriber(args.node + '/report', MonitorReport, reports.on_report, queue_size=10000)
    bag = rosbag.Bag(args.bag)
    topics = sorted(t for t, info in bag.get_type_and_topic_info().topics.items()
                    if info.msg_type == 'sensor_msgs/JointState')
    publishers = {t: rospy.Publisher(t, JointState, queue_size=10) for t in topics}
    if not wait_until(lambda: all(p.get_num_connections() > 0 for p in publishers.values()),
                      3 * args.timeout):
        print('%s: the monitor never subscribed to %s' % (title, ', '.join(topics)))
        return 1
    for target in args.grasp:
        link, _, obj = target.partition(':')
        rospy.wait_for_service(args.node + '/set_grasp_target', timeout=3 * args.timeout)
        result = rospy.ServiceProxy(args.node + '/set_grasp_target', SetGraspTarget)(
            link, obj, True)
        if not result.success:
            print('%s: set_grasp_target %s failed: %s' % (title, target, result.message))
            return 1
    # Wait until ~report is connected too, or the first reports would be lost.
    report_topic = args.node + '/report'
    if not wait_until(lambda: any(
            report_topic == t for t, _ in rospy.get_published_topics(args.node)), 3 * args.timeout):
        print('%s: the monitor does not publish %s' % (title, report_topic))
        return 1

    print('=== %s: %s' % (title, args.bag))
    print('  %-8s %-8s %-7s %-45s %s' % ('time_s', 'message', 'event', 'pair', 'distance_m'))
    start_count = reports.count()
    first_stamp = None
    wall_start = time.time()
    active = {}  # pair -> [first time, closest distance]
    published = 0
    first_warning = None
    warning_reports = 0
    stop_reports = 0
    stop_reasons = {}  # reason with its numbers removed -> reports
    cycle_times = []
    missing = 0
    for topic, msg, _ in bag.read_messages(topics=topics):
        t_bag = msg.header.stamp.to_sec()
        if first_stamp is None:
            first_stamp = t_bag
        t_s = t_bag - first_stamp
        if args.rate > 0.0:
            delay = wall_start + t_s / args.rate - time.time()
            if delay > 0.0:
                time.sleep(delay)
        msg.header.stamp = rospy.Time.now()
        publishers[topic].publish(msg)
        report = reports.wait_for(start_count + published, args.timeout)
        published += 1
        if report is None:
            missing += 1
            print('  %8.2f %8d no report within %.1f s' % (t_s, published, args.timeout))
            break
        cycle_times.append(report.cycle_time_s)
        stop_reports += report.stop
        if report.stop:
            reason = re.sub(r'\b[0-9]+(\.[0-9]+)?\b', 'N', report.stop_reason)
            stop_reasons[reason] = stop_reasons.get(reason, 0) + 1
        pairs = {}
        for w in report.warnings:
            pairs['%s -- %s' % (w.primitive_a_name, w.primitive_b_name)] = w.distance_m
        if pairs:
            warning_reports += 1
            if first_warning is None:
                name = sorted(pairs)[0]
                first_warning = (published, t_s, name, pairs[name])
        for pair, distance in sorted(pairs.items()):
            if pair not in active:
                active[pair] = [t_s, distance]
                print('  %8.2f %8d %-7s %-45s %.4f' % (t_s, published, 'WARN', pair, distance))
            active[pair][1] = min(active[pair][1], distance)
        for pair in sorted(set(active) - set(pairs)):
            since, closest = active.pop(pair)
            print('  %8.2f %8d %-7s %-45s closest %.4f over %.2f s' % (
                t_s, published, 'clear', pair, closest, t_s - since))
    for pair, (since, closest) in sorted(active.items()):
        print('  %8s %8s %-7s %-45s closest %.4f since %.2f s' % (
            '(end)', '', 'still', pair, closest, since))
    bag.close()

    cycle_times.sort()
    print('--- %s summary: %d messages replayed, %d reports (one cycle each), %d with warnings'
          % (title, published, published - missing, warning_reports))
    if first_warning:
        print('    first warning: message %d at %.2f s: %s at %.4f m' % first_warning)
    else:
        print('    first warning: none')
    print('    stop requested in %d of %d reports' % (stop_reports, published - missing))
    for reason, count in sorted(stop_reasons.items(), key=lambda item: -item[1]):
        print('      %5d  %s' % (count, reason))
    print('    node cycle time: p50 %.1f us, p99 %.1f us, max %.1f us' % (
        percentile(cycle_times, 50) * 1e6, percentile(cycle_times, 99) * 1e6,
        (cycle_times[-1] if cycle_times else float('nan')) * 1e6))
    return 1 if missing else 0


if __name__ == '__main__':
    sys.exit(main())
