#!/usr/bin/env python3
"""docs/ros.md's command blocks, as a user pastes them: every indented line (with its backslash continuations)
that talks to the node /top_sim with `rosservice call`, `rostopic pub -1`, `rostopic echo -n` or
`rosrun dynamic_reconfigure dynparam` runs in bash, in the order of the file, against a node on the default scene;
each must exit 0 and no service may answer `success: False` (docs/ros.md, "Examples", says so)."""
import re
import subprocess
import sys
import unittest

import rospy
import rostest

RUN = re.compile(r'^(rosservice call /top_sim/|rostopic pub -1 /top_sim/|rostopic echo -n \d+ /|'
                 r'rosrun dynamic_reconfigure dynparam \w+ /top_sim\b)')


def commands(path):
    """The runnable command lines of the indented blocks, continuations joined."""
    found, pending = [], None
    for line in open(path):
        if pending is not None:
            pending += '\n' + line.rstrip('\n')
            if not line.rstrip().endswith('\\'):
                found.append(pending)
                pending = None
            continue
        if not line.startswith('    '):
            continue
        text = line[4:].rstrip('\n')
        if RUN.match(text):
            if text.rstrip().endswith('\\'):
                pending = text
            else:
                found.append(text)
    return found


class DocsCommands(unittest.TestCase):
    def test_every_command_of_docs_ros_md_works_as_pasted(self):
        cmds = commands(rospy.get_param('~docs'))
        self.assertGreaterEqual(len(cmds), 12, 'the docs lost their examples? found %d' % len(cmds))
        rospy.wait_for_service('/top_sim/reset', timeout=60.0)
        for cmd in cmds:
            p = subprocess.run(['bash', '-c', cmd], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               universal_newlines=True, timeout=60)
            rospy.loginfo('docs/ros.md: %s -> %d', cmd, p.returncode)
            self.assertEqual(p.returncode, 0, '%s\nfailed:\n%s' % (cmd, p.stdout))
            self.assertNotIn('success: False', p.stdout, '%s\nrefused:\n%s' % (cmd, p.stdout))


if __name__ == '__main__':
    rospy.init_node('test_docs_commands')
    rostest.rosrun('top_sim', 'test_docs_commands', DocsCommands, sys.argv)
