"""A large ISO 14649 file with explicit toolpaths, for the Part 21 speed rows (bench only).

The conventions are those the reader understands and tests/test_stepnc_freeform.py checks (NIST's
ex1E style): a 600 x 400 x 30 plate, a grid of 40 x 24 closed pockets 4 mm deep, each milled by a
FREEFORM_OPERATION whose TOOLPATH_LIST holds CUTTER_LOCATION_TRAJECTORYs of POLYLINEs in the
pocket's coordinates: a raster finishing pass with a cutter location every 0.05 mm over a shallow
dish (so no two points are alike), in polylines of ``POINTS_PER_LINE`` points; each point is its
own CARTESIAN_POINT, as exporters write them.  Instances are written ``#n= NAME(...);`` one a line.
"""
from __future__ import annotations

import math

POCKET = (40.0, 24.0, 4.0)      # length, width, depth (mm)
STEP = 0.05                     # mm between cutter locations along a raster line
STEPOVER = 1.0                  # mm between raster lines
POINTS_PER_LINE = 400

_HEAD = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('KEZURI BENCH: EXPLICIT TOOLPATHS'),'2;1');
FILE_NAME('bigfile.stp','2026-11-27T00:00:00',('kezuri'),(''),'','','');
FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));
ENDSEC;
DATA;
#1= PROJECT('BIG FREEFORM',#2,(#3),$,$,$);
#3= WORKPIECE('PLATE',$,0.01,$,$,#7,());
#4= AXIS2_PLACEMENT_3D('WORKPIECE ORIGIN',#10,#11,#12);
#5= SETUP('SETUP1',#4,#6,(#8));
#6= PLANE('SECURITY PLANE',#9);
#7= BLOCK('PLATE BLOCK',#13,600.000,400.000,30.000);
#8= WORKPIECE_SETUP(#3,#4,$,$,());
#9= AXIS2_PLACEMENT_3D('SECURITY PLANE',#14,#11,#12);
#10= CARTESIAN_POINT('ORIGIN',(0.000,0.000,0.000));
#11= DIRECTION('Z AXIS',(0.000,0.000,1.000));
#12= DIRECTION('X AXIS',(1.000,0.000,0.000));
#13= AXIS2_PLACEMENT_3D('BLOCK CORNER',#15,#11,#12);
#14= CARTESIAN_POINT('SECURITY PLANE',(0.000,0.000,20.000));
#15= CARTESIAN_POINT('BLOCK CORNER',(0.000,0.000,-30.000));
#20= ENDMILL(#21,2,.RIGHT.,.F.,$);
#21= MILLING_TOOL_DIMENSION(6.000,$,$,25.000,0.000,$,$);
#22= MILLING_CUTTING_TOOL('ENDMILL 6MM',#20,(#23),$,$,$);
#23= CUTTING_COMPONENT(25.000,$,$,$,$);
#24= MILLING_TECHNOLOGY(0.020,.TCP.,$,-100.000,$,.F.,.F.,.F.,$);
#25= MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());
#46= PLANAR_POCKET_BOTTOM_CONDITION();
#47= TOLERANCED_LENGTH_MEASURE(5.000,#90);
#49= TOLERANCED_LENGTH_MEASURE(24.000,#90);
#39= TOLERANCED_LENGTH_MEASURE(40.000,#90);
#90= PLUS_MINUS_VALUE(0.010,0.010,3);
"""


def _pocket_lines(x0: float, y0: float) -> list:
    """Raster lines (lists of (x, y, z) in pocket coordinates) over the pocket's floor region
    inset by the tool radius, z a shallow dish under the floor's top."""
    length, width, depth = POCKET
    half_x, half_y = length / 2 - 3.5, width / 2 - 3.5
    lines = []
    n = round(2 * half_x / STEP)
    for k, y in enumerate(-half_y + STEPOVER * i for i in range(int(2 * half_y / STEPOVER) + 1)):
        xs = [-half_x + STEP * i for i in range(n + 1)]
        if k % 2:
            xs.reverse()
        lines.append([(x, y, -depth + 0.5 * (x * x / (half_x * half_x) + y * y / (half_y * half_y)) - 1.0
                       + 0.001 * math.sin(x0 + y0 + x)) for x in xs])
    return lines


def explicit_toolpath_file(megabytes: float = 50.0) -> str:
    """A file of about ``megabytes`` MB (decimal): as many pockets as it takes."""
    out = [_HEAD]
    size = len(_HEAD)
    target = megabytes * 1e6
    steps, n = [], 1000
    pocket = 0
    while size < target - 2000:
        x, y = 30 + (pocket % 13) * 45, 20 + (pocket // 13) % 14 * 28
        base = n
        block = [f"#{base}= CLOSED_POCKET('POCKET{pocket}',#3,(#{base + 5}),#{base + 1},#{base + 3},(),$,#46,$,#47,"
                 f"#{base + 9});",
                 f"#{base + 1}= AXIS2_PLACEMENT_3D('POCKET{pocket}',#{base + 2},#11,#12);",
                 f"#{base + 2}= CARTESIAN_POINT('POCKET{pocket}: LOCATION',({x:.3f},{y:.3f},0.000));",
                 f"#{base + 3}= PLANE('POCKET{pocket} DEPTH',#{base + 4});",
                 f"#{base + 4}= AXIS2_PLACEMENT_3D('POCKET{pocket} DEPTH',#{base + 8},#11,#12);",
                 f"#{base + 8}= CARTESIAN_POINT('POCKET{pocket}: DEPTH',(0.000,0.000,-{POCKET[2]:.3f}));",
                 f"#{base + 9}= RECTANGULAR_CLOSED_PROFILE($,#49,#39);",
                 f"#{base + 5}= FREEFORM_OPERATION(#{base + 7},$,'FINISH POCKET{pocket}',5.000,$,#22,#24,#25,"
                 f"$,$,$,$);",
                 f"#{base + 6}= MACHINING_WORKINGSTEP('WS POCKET{pocket}',#6,#{base},#{base + 5},$);"]
        n = base + 10
        trajectories = []
        points = [p for line in _pocket_lines(x, y) for p in line]
        for start in range(0, len(points) - 1, POINTS_PER_LINE - 1):
            chunk = points[start:start + POINTS_PER_LINE]
            first = n
            for px, py, pz in chunk:
                block.append(f"#{n}= CARTESIAN_POINT('',({px:.4f},{py:.4f},{pz:.4f}));")
                n += 1
            refs = ",".join(f"#{k}" for k in range(first, n))
            block.append(f"#{n}= POLYLINE('',({refs}));")
            block.append(f"#{n + 1}= CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,$,$,#{n},$,$);")
            trajectories.append(n + 1)
            n += 2
        block.append(f"#{base + 7}= TOOLPATH_LIST(({','.join(f'#{t}' for t in trajectories)}));")
        text = "\n".join(block) + "\n"
        out.append(text)
        size += len(text)
        steps.append(base + 6)
        pocket += 1
    out.append(f"#2= WORKPLAN('MAIN WORKPLAN',({','.join(f'#{s}' for s in steps)}),$,#5,$);\n")
    out.append("ENDSEC;\nEND-ISO-10303-21;\n")
    return "".join(out)
