#!/usr/bin/env python3
"""Saves a PNG of one X window (found by title) once it is mapped; used by rviz_screenshot.sh under Xvfb.

Needs only python3-pil (built with XCB) and x11-utils' xwininfo, both Debian packages.
Usage: grab_window.py --title RViz --out FILE.png [--display :99] [--timeout 60] [--min-size 200]
Exit status 0 on success, 1 if no such window appears in time or the image is blank.
"""
import argparse
import os
import re
import subprocess
import sys
import time

from PIL import ImageGrab, ImageStat

# One line of `xwininfo -root -tree`: id "title": (class) WxH+x+y  +absx+absy
LINE = re.compile(r'^\s*(0x[0-9a-f]+) "(?P<title>[^"]*)".*?(?P<w>\d+)x(?P<h>\d+)[+-]-?\d+[+-]-?\d+\s+\+(?P<x>-?\d+)\+(?P<y>-?\d+)')


def find_window(display, title, min_size):
    out = subprocess.run(['xwininfo', '-display', display, '-root', '-tree'],
                         capture_output=True, text=True, check=False).stdout
    for line in out.splitlines():
        m = LINE.match(line)
        if m and title in m.group('title') and int(m.group('w')) >= min_size and int(m.group('h')) >= min_size:
            return tuple(int(m.group(k)) for k in ('x', 'y', 'w', 'h'))
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--title', default='RViz')
    ap.add_argument('--out', required=True)
    ap.add_argument('--display', default=os.environ.get('DISPLAY', ':0'))
    ap.add_argument('--timeout', type=float, default=60.0)
    ap.add_argument('--min-size', type=int, default=200)
    args = ap.parse_args()

    deadline = time.time() + args.timeout
    geometry = None
    while geometry is None and time.time() < deadline:
        geometry = find_window(args.display, args.title, args.min_size)
        if geometry is None:
            time.sleep(0.5)
    if geometry is None:
        print(f'grab_window: no window titled "{args.title}" on {args.display} within {args.timeout} s', file=sys.stderr)
        return 1
    x, y, w, h = geometry
    image = ImageGrab.grab(bbox=(x, y, x + w, y + h), xdisplay=args.display).convert('RGB')
    # A uniform image means nothing was drawn (window not yet painted or GL failed).
    if max(ImageStat.Stat(image).stddev) < 1.0:
        print(f'grab_window: window "{args.title}" is blank', file=sys.stderr)
        return 1
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    image.save(args.out, optimize=True)
    print(f'grab_window: {w}x{h} window "{args.title}" saved to {args.out}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
