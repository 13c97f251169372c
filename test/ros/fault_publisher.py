#!/usr/bin/python3
"""A stand-in for the arms' joint state publishers in the fault rostests: both arms on their two
topics at ~rate_hz, a slow swing of joint 2 around the home pose (clear of everything). With
~lifetime_s > 0 it exits after that many wall seconds, so that roslaunch's respawn turns it into
a publisher that restarts mid-task."""
import math
import sys
import time

import rospy
from sensor_msgs.msg import JointState

from acm_test_util import LEFT_JOINTS, RIGHT_JOINTS, joint_state

# Amplitude (rad) and angular frequency (rad/s) of the swing: small and slow, far from any
# obstacle and well within the per-cycle motion bound.
SWING_RAD = 0.2
SWING_RAD_PER_S = 0.5


def main():
    rospy.init_node('fault_publisher')
    rate_hz = rospy.get_param('~rate_hz', 50.0)
    lifetime_s = rospy.get_param('~lifetime_s', 0.0)
    left = rospy.Publisher('left_arm/joint_states', JointState, queue_size=10)
    right = rospy.Publisher('right_arm/joint_states', JointState, queue_size=10)
    started = time.time()
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        if lifetime_s > 0.0 and time.time() - started > lifetime_s:
            rospy.loginfo('fault_publisher: lifetime over, exiting (respawn restarts it)')
            return 0
        swing = SWING_RAD * math.sin(SWING_RAD_PER_S * time.time())
        positions = [0.0, swing, 0.0, 0.0, 0.0, 0.0, 0.0]
        left.publish(joint_state(LEFT_JOINTS, positions))
        right.publish(joint_state(RIGHT_JOINTS, positions))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
    return 0


if __name__ == '__main__':
    sys.exit(main())
