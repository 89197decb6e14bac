#!/usr/bin/env python3
"""Prints the 'QMainWindow State' hex for rviz/top_sim.rviz: Displays and Views docked left, the Top control panel
docked right over the whole height (it fits there without scrolling), Time at the bottom.

rviz restores its dock layout from this QMainWindow::saveState() blob; without it, under Xvfb the docks take
the whole window and the 3D view is 0 px wide. The blob is Qt 5's QDataStream encoding (big-endian), written
here from the layout we want instead of being saved by hand from a GUI session.
Usage: scripts/rviz_layout.py [WIDTH HEIGHT [LEFT_DOCK_WIDTH [RIGHT_DOCK_WIDTH]]]   (defaults 1280 800 300 340)
"""
import struct
import sys

LEFT, RIGHT, TOP, BOTTOM = 0, 1, 2, 3   # QInternal::DockPosition
VERTICAL, HORIZONTAL = 2, 1            # Qt::Orientation
MENU_H, TOOLBAR_H, STATUS_H, TIME_H, SEP = 22, 40, 29, 57, 4   # rviz's widget heights under Xvfb [px]


def i32(v):
    return struct.pack('>i', v)


def u8(v):
    return struct.pack('>B', v)


def qstring(s):
    b = s.encode('utf-16-be')
    return struct.pack('>I', len(b)) + b


def dock_item(name, pos, size, visible=True):
    # WidgetMarker, objectName, flags (1 = visible, not floating), pos, size, min and max (ignored on restore).
    return u8(0xfb) + qstring(name) + u8(1 if visible else 0) + i32(pos) + i32(size) + i32(0) + i32(0xffffff)


def dock_area(position, width, height, orientation, items):
    # position, area size, SequenceMarker, orientation, item count, items.
    return i32(position) + i32(width) + i32(height) + u8(0xfc) + u8(orientation) + i32(len(items)) + b''.join(items)


def main():
    width = int(sys.argv[1]) if len(sys.argv) > 1 else 1280
    height = int(sys.argv[2]) if len(sys.argv) > 2 else 800
    left_w = int(sys.argv[3]) if len(sys.argv) > 3 else 300
    right_w = int(sys.argv[4]) if len(sys.argv) > 4 else 340
    body_h = height - MENU_H - TOOLBAR_H - STATUS_H      # between the toolbar and the status bar
    upper_h = body_h - TIME_H - SEP                      # left dock and 3D view
    displays_h = int(upper_h * 0.62)
    views_h = upper_h - displays_h - SEP
    central_w = width - left_w - SEP - right_w - SEP

    docks = (u8(0xfd) + i32(3)
             + dock_area(LEFT, left_w, upper_h, VERTICAL,
                         [dock_item('Displays', 0, displays_h), dock_item('Views', displays_h + SEP, views_h)])
             + dock_area(RIGHT, right_w, upper_h, VERTICAL, [dock_item('Top control', 0, upper_h)])
             + dock_area(BOTTOM, width, TIME_H, HORIZONTAL, [dock_item('Time', 0, width)])
             + i32(central_w) + i32(upper_h)
             + i32(4) + i32(4) + i32(8) + i32(8))    # corners: top-left/right to Top, bottom ones to Bottom
    # ToolBarStateMarkerEx, one line in the top area holding rviz's "Tools" toolbar (shown, pos 0, default size).
    toolbars = (u8(0xfc) + i32(1) + i32(TOP) + i32(1) + qstring('Tools') + u8(1) + i32(0) + i32(-1)
                + i32(0) + i32(0))
    blob = i32(0xff) + i32(0) + docks + toolbars     # VersionMarker, user version 0
    print(blob.hex())


if __name__ == '__main__':
    main()
