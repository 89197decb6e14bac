#!/usr/bin/env python3
"""Prints the 'QMainWindow State' hex for rviz/top_sim.rviz: Displays, Views and the Top control panel as tabs of
the left dock, Top control on top (it gets the dock's whole height and fits it without scrolling). No Time panel
(rviz's ROS and wall clocks): its 61 px of height go to the dock, so the panel's fields and its answer line fit
the 1280 x 800 window (issue 46), and to the 3D view.

rviz restores its dock layout from this QMainWindow::saveState() blob; without it, under Xvfb the docks take
the whole window and the 3D view is 0 px wide. The blob is Qt 5's QDataStream encoding (big-endian), written
here from the layout we want instead of being saved by hand from a GUI session.
Usage: scripts/rviz_layout.py [WIDTH HEIGHT [LEFT_DOCK_WIDTH]]   (defaults 1280 800 340)
"""
import struct
import sys

LEFT, TOP = 0, 2                       # QInternal::DockPosition
VERTICAL = 2                           # Qt::Orientation
MENU_H, TOOLBAR_H, STATUS_H, SEP = 22, 40, 29, 4   # rviz's widget heights under Xvfb [px]


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


def tab_group(pos, size, orientation, current, items):
    # A nested item holding tabbed docks (what QMainWindow::tabifyDockWidget makes): SequenceMarker, pos, size,
    # min and max, then the group: TabMarker, the index of the tab on top, orientation, item count, items.
    return (u8(0xfc) + i32(pos) + i32(size) + i32(0) + i32(0)
            + u8(0xfa) + i32(current) + u8(orientation) + i32(len(items)) + b''.join(items))


def main():
    width = int(sys.argv[1]) if len(sys.argv) > 1 else 1280
    height = int(sys.argv[2]) if len(sys.argv) > 2 else 800
    left_w = int(sys.argv[3]) if len(sys.argv) > 3 else 340
    body_h = height - MENU_H - TOOLBAR_H - STATUS_H      # between the toolbar and the status bar
    upper_h = body_h                                     # left dock and 3D view
    central_w = width - left_w - SEP
    # Displays, Views and Top control as tabs of the left dock, Top control on top: the panel gets the dock's
    # whole height and fits it without scrolling, and the 3D view keeps the window's width less one dock.
    tabs = [dock_item(name, 0, upper_h) for name in ('Displays', 'Views', 'Top control')]
    left = i32(LEFT) + i32(left_w) + i32(upper_h) + u8(0xfc) + u8(VERTICAL) + i32(1) + tab_group(
        0, upper_h, VERTICAL, 2, tabs)

    docks = (u8(0xfd) + i32(1) + left
             + i32(central_w) + i32(upper_h)
             + i32(4) + i32(4) + i32(8) + i32(8))    # corners: top-left/right to Top, bottom ones to Bottom
    # ToolBarStateMarkerEx, one line in the top area holding rviz's "Tools" toolbar (shown, pos 0, default size).
    toolbars = (u8(0xfc) + i32(1) + i32(TOP) + i32(1) + qstring('Tools') + u8(1) + i32(0) + i32(-1)
                + i32(0) + i32(0))
    blob = i32(0xff) + i32(0) + docks + toolbars     # VersionMarker, user version 0
    print(blob.hex())


if __name__ == '__main__':
    main()
