#!/usr/bin/env python3
"""Clicks the left mouse button at a point of the X display ($DISPLAY), through the XTEST extension (libXtst, which
Xvfb serves): what rviz_screenshot.sh's TOP_SIM_SHOT_SETUP needs to press a panel button, without xdotool.
Usage: x_click.py X Y   (screen pixels). Exit status 1 when the display cannot be opened."""
import ctypes
import sys
import time


def main():
    if len(sys.argv) != 3:
        sys.exit('usage: x_click.py X Y')
    x, y = int(sys.argv[1]), int(sys.argv[2])
    xlib = ctypes.CDLL('libX11.so.6')
    xtst = ctypes.CDLL('libXtst.so.6')
    xlib.XOpenDisplay.restype = ctypes.c_void_p
    display = xlib.XOpenDisplay(None)
    if not display:
        sys.exit('x_click.py: cannot open the display (is DISPLAY set?)')
    display = ctypes.c_void_p(display)
    xtst.XTestFakeMotionEvent(display, -1, x, y, 0)
    xlib.XFlush(display)
    time.sleep(0.2)  # Qt sees the pointer over the button before the press, as after a real move
    for pressed in (True, False):
        xtst.XTestFakeButtonEvent(display, 1, pressed, 0)
        xlib.XFlush(display)
        time.sleep(0.05)
    xlib.XCloseDisplay(display)


if __name__ == '__main__':
    main()
