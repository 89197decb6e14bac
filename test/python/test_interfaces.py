"""LCM's top_state_t carries TopState's fields (docs/interfaces.md: "same fields as TopState"): both definitions are
parsed and compared; the only differences are the ones the two formats force, listed here once."""
import os
import re

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')

# TopState fields that LCM spells differently (it has no header, Pose or Twist types).
MSG_TO_LCM = {
    'header': [],                                     # stamp: utime carries the time
    'sim_time': ['utime'],                            # [s] -> [us]
    'pose': ['position', 'orientation'],
    'twist': ['velocity', 'angular_velocity'],
}


def msg_fields(path):
    fields = []
    for line in open(path):
        line = line.split('#')[0].strip()
        m = re.match(r'^[A-Za-z0-9_/\[\]]+\s+([a-z_][a-z0-9_]*)$', line)  # constants have '=' and do not match
        if m:
            fields.append(m.group(1))
    return fields


def lcm_fields(path):
    fields = []
    for line in open(path):
        m = re.match(r'^\s*(int8_t|int16_t|int32_t|int64_t|double|float|boolean|string)\s+([a-z_][a-z0-9_]*)', line)
        if m:
            fields.append(m.group(2))
    return fields


def test_lcm_has_the_fields_of_top_state():
    msg = msg_fields(os.path.join(ROOT, 'msg', 'TopState.msg'))
    lcm = lcm_fields(os.path.join(ROOT, 'lcm', 'top_state_t.lcm'))
    assert 'regime_name' in msg and 'paused' in msg  # the parser reads the message
    expected = set()
    for f in msg:
        expected.update(MSG_TO_LCM.get(f, [f]))
    assert sorted(expected - set(lcm)) == [], 'TopState fields missing from top_state_t'
    assert sorted(set(lcm) - expected) == [], 'top_state_t fields TopState does not have'
