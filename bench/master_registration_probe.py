#!/usr/bin/env python3
"""How long a ROS master takes to register N publishers, one topic each, from one node (issue 35: a node with
10,000 tops advertises 2 topics per top at start-up). Run against a private master:
    roscore -p PORT &  ROS_MASTER_URI=http://localhost:PORT bench/master_registration_probe.py N
Prints the elapsed seconds after every 500 registrations."""
import time, sys, rospy
from std_msgs.msg import Float64
rospy.init_node('adv_probe', anonymous=True, disable_signals=True)
pubs = []
n = int(sys.argv[1])
t0 = time.time()
marks = {}
for i in range(n):
    pubs.append(rospy.Publisher('/probe/t%05d/top_state' % i, Float64, queue_size=1))
    if (i + 1) % 500 == 0:
        marks[i + 1] = time.time() - t0
print({k: round(v, 2) for k, v in marks.items()})
