"""Run by ParaView's pvpython: opens .pvd collections with ParaView's own reader and reports what
ParaView sees, as JSON, for test_paraview_open.py to compare with the files.

    pvpython paraview_read_pvd.py REPORT.json COLLECTION.pvd [COLLECTION.pvd ...]

For each collection: its time steps and, at each, every part's dataset type, point and cell
counts, point-array names and the mean of its points.
"""
import json
import sys

from paraview import servermanager
from paraview.simple import Delete, PVDReader


def dataset_report(dataset):
    n = dataset.GetNumberOfPoints()
    mean = [0.0, 0.0, 0.0]
    points = dataset.GetPoints()
    for i in range(n):
        p = points.GetPoint(i)
        for k in range(3):
            mean[k] += p[k] / n
    data = dataset.GetPointData()
    return {
        "type": dataset.GetClassName(),
        "points": n,
        "cells": dataset.GetNumberOfCells(),
        "point_arrays": sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays())),
        "mean": mean,
    }


def collection_report(path):
    reader = PVDReader(FileName=path)
    steps = []
    try:
        times = [float(t) for t in reader.TimestepValues]
    except TypeError:  # one time step: a number, not a list
        times = [float(reader.TimestepValues)]
    for time in times:
        reader.UpdatePipeline(time)
        tree = servermanager.Fetch(reader)
        # One block per part (the .pvd's part numbers in order), each holding that part's dataset;
        # a collection of one part is that part's dataset itself.
        if not tree.IsA("vtkMultiBlockDataSet"):
            steps.append({"time": time, "parts": [dataset_report(tree)]})
            continue
        parts = []
        for b in range(tree.GetNumberOfBlocks()):
            block = tree.GetBlock(b)
            while block is not None and block.IsA("vtkMultiBlockDataSet"):
                block = block.GetBlock(0) if block.GetNumberOfBlocks() else None
            parts.append(dataset_report(block) if block is not None else None)
        steps.append({"time": time, "parts": parts})
    Delete(reader)
    return steps


def main():
    report = {path: collection_report(path) for path in sys.argv[2:]}
    with open(sys.argv[1], "w") as out:
        json.dump(report, out)


main()
