"""One command schema (include/top_sim/command_fields.hpp, exposed as top_sim.command_fields()): Python's apply,
scene events and dynamic_reconfigure (cfg/TopSim.cfg) take its fields with its limits."""
import math
import os
import re

import pytest
import yaml

import top_sim

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
CFG_NAME = {'inclination': 'alpha'}  # dynamic_reconfigure's public name of a command field, where it differs


def fields():
    return {f['name']: f for f in top_sim.command_fields()}


def cfg_entries():
    """name -> (description, default, has min/max) of each gen.add in cfg/TopSim.cfg."""
    text = open(os.path.join(ROOT, 'cfg', 'TopSim.cfg')).read()
    out = {}
    for m in re.finditer(r'gen\.add\("(\w+)",\s*\w+,\s*\d+,\s*"([^"]*)",\s*([^,)]+)([^)\n]*)\)', text):
        out[m.group(1)] = (m.group(2), m.group(3), 'min' in m.group(4) or 'max' in m.group(4))
    return out


def admits(f, v):
    lo_ok = v > f['lower'] if f['lower_open'] else v >= f['lower']
    hi_ok = v < f['upper'] if f['upper_open'] else v <= f['upper']
    return math.isfinite(v) and lo_ok and hi_ok


def test_limits_are_those_of_limits_hpp():
    f = fields()
    assert f['inclination']['upper'] == math.pi / 2 and f['inclination']['lower'] == -math.pi / 2
    assert f['inclination']['upper_open'] and f['inclination']['lower_open']
    assert f['spin']['upper'] == 1.0e6 and not f['spin']['upper_open']  # limits.hpp kMaxSpin, included
    assert f['rotor_spin']['upper'] == f['spin']['upper']
    assert (f['restitution']['lower'], f['restitution']['upper']) == (0.0, 1.0)


def test_reconfigure_fields_state_the_schemas_range_and_are_not_clamped():
    cfg = cfg_entries()
    shared = [n for n in fields() if CFG_NAME.get(n, n) in cfg]
    assert set(shared) >= {'inclination', 'spin', 'patch_radius', 'rolling_resistance', 'spin_drag', 'drag'}
    for name in shared:
        description, default, clamped = cfg[CFG_NAME.get(name, name)]
        f = fields()[name]
        assert description.endswith(f['range']), (name, description, f['range'])
        assert not clamped, name + ": dynamic_reconfigure would clamp silently; the core refuses instead"
        assert admits(f, float(default)), (name, default)


@pytest.mark.parametrize('name', [f['name'] for f in top_sim.command_fields()])
def test_apply_refuses_each_field_beyond_its_limit_naming_field_value_and_range(name):
    f = fields()[name]
    bad = f['upper'] * 2 if math.isfinite(f['upper']) else f['lower'] - 1.0
    sim = top_sim.Simulator(top_sim.load_scene('gyro_reversal'))  # a rotor: rotor_spin and rotor_coupling apply
    with pytest.raises(ValueError) as e:
        sim.apply({name: bad})
    text = str(e.value)
    assert text.startswith(name + ' = ') and f['range'] in text, text


@pytest.mark.parametrize('name', [f['name'] for f in top_sim.command_fields()])
def test_scene_events_take_every_field_with_its_limit(name):
    f = fields()[name]
    bad = f['upper'] * 2 if math.isfinite(f['upper']) else f['lower'] - 1.0
    scene = yaml.safe_load(open(os.path.join(ROOT, 'config', 'scenes', 'gyro_reversal.yaml')))  # has a rotor
    scene['events'] = [{'t': 1.0, name: bad}]
    with pytest.raises(top_sim.SceneError) as e:
        top_sim.load_scene(scene)
    assert 'events[0].' + name in str(e.value) and f['range'] in str(e.value), str(e.value)
