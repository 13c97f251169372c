#!/usr/bin/python3
"""The scene's frame-bound camera calibration for the fault rostests: world -> camera_link
(xyz 1.6 0 2.4 m, rpy 0 0.6 0 rad) on /tf_static, latched. Written against tf2_msgs only,
because neither tf2_ros's static_transform_publisher nor its Python module is installed by
scripts/setup."""
import math

import rospy
from geometry_msgs.msg import TransformStamped
from tf2_msgs.msg import TFMessage

PITCH_RAD = 0.6


def main():
    rospy.init_node('fault_camera_tf')
    pub = rospy.Publisher('/tf_static', TFMessage, queue_size=1, latch=True)
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id = 'world'
    t.child_frame_id = 'camera_link'
    t.transform.translation.x = 1.6
    t.transform.translation.z = 2.4
    t.transform.rotation.y = math.sin(0.5 * PITCH_RAD)
    t.transform.rotation.w = math.cos(0.5 * PITCH_RAD)
    pub.publish(TFMessage(transforms=[t]))
    rospy.spin()


if __name__ == '__main__':
    main()
