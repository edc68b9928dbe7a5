"""Reading STEP files back with OpenCascade's own reader, for the B-rep tests (an
independent route from gear3d's writer): the shape, its sub-shapes and its validity."""


def read_step(path):
    """The shape in a STEP file, read by OCC's STEPControl_Reader."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    r = STEPControl_Reader()
    assert r.ReadFile(str(path)) == IFSelect_RetDone
    assert r.TransferRoots() >= 1
    return r.OneShape()


def sub_shapes(shape, kind):
    """The sub-shapes of one kind ('solid', 'face', 'edge', ...) of ``shape``, in order."""
    from OCP import TopAbs
    from OCP.TopExp import TopExp_Explorer
    ex = TopExp_Explorer(shape, getattr(TopAbs, "TopAbs_" + kind.upper()))
    out = []
    while ex.More():
        out.append(ex.Current())
        ex.Next()
    return out


def is_valid(shape) -> bool:
    """OpenCascade's BRepCheck_Analyzer verdict on ``shape``."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    return BRepCheck_Analyzer(shape).IsValid()
