"""FreeCAD's V-carve on given outlines, headless: run by ``freecadcmd`` from bench_vcarve.py.

    freecadcmd bench/freecad_vcarve.py   (reads $KEZURI_VCARVE_IN, writes $KEZURI_VCARVE_OUT, JSON)

The input holds the sign's faces as loops (mm); each face becomes a Part face (outer wire and
counters, FaceMakerBullseye) and the CAM (Path) workbench's V-carve operation computes its path on
them: ``ObjectVcarve.buildPathMedial`` (FreeCAD 0.20's PathVcarve.py), the step that builds the
Voronoi diagram (Path.Voronoi, Boost.Polygon), keeps the medial axis and gives each point its depth.
A full Job (model, stock, tool controller) needs FreeCAD's GUI modules for its defaults, so the
operation's object is a plain stand-in carrying the same properties with FreeCAD's defaults
(Discretize 0.01, Colinear 10, the geometry tolerance) and a 60 deg V-bit of 25.4 mm.
"""
import json
import math
import os
import time

import FreeCAD
import Part
import PathScripts.PathPreferences as PathPreferences
import PathScripts.PathVcarve as PathVcarve


class Value:
    def __init__(self, value):
        self.Value = value

    def __float__(self):
        return float(self.Value)

    def __ge__(self, other):
        return self.Value >= other


class Tool:
    Diameter = 25.4
    TipDiameter = 0.0
    CuttingEdgeAngle = Value(60.0)


class Controller:
    Tool = Tool()
    HorizFeed = Value(1000.0)
    VertFeed = Value(400.0)


class Operation:
    Discretize = 0.01
    Colinear = 10.0
    Tolerance = PathPreferences.defaultGeometryTolerance()
    SafeHeight = Value(5.0)
    FinalDepth = Value(-100.0)
    ToolController = Controller()


class Model:
    class Shape:
        class BoundBox:
            ZMax = 0.0


def faces_of(groups):
    faces = []
    for loops in groups:
        wires = []
        for loop in loops:
            points = [FreeCAD.Vector(x, y, 0) for x, y in loop]
            wires.append(Part.makePolygon(points + points[:1]))
        faces.extend(Part.makeFace(wires, "Part::FaceMakerBullseye").Faces)
    return faces


def main():
    data = json.load(open(os.environ["KEZURI_VCARVE_IN"]))
    faces = faces_of(data["groups"])
    op = object.__new__(PathVcarve.ObjectVcarve)
    op.model = [Model()]
    best, moves = math.inf, 0
    for _ in range(3):
        started = time.process_time()
        op.buildPathMedial(Operation(), faces)
        best = min(best, time.process_time() - started)
        moves = len(op.commandlist)
    with open(os.environ["KEZURI_VCARVE_OUT"], "w") as stream:
        json.dump({"seconds": best, "commands": moves, "faces": len(faces), "version": FreeCAD.Version()[:3]}, stream)


main()
