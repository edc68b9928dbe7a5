"""Issue #27: a face gear's B-rep STEP at a coarse tolerance (1 mm) with the outer radius at
the pointing limit crashed in OpenCascade's GC_MakeArcOfCircle (the tip land's arc was three
points collinear to OCC's precision). Now the arc is its chord (sagitta < 1 nm), and a tip land
narrower than the sewing tolerance (40/20 at the limit: 2.6e-7 mm, which sewing merged into a
degenerate edge: an invalid solid) is closed to a point: the CLI writes a STEP that
OpenCascade reads back as one valid solid (exit 0).
"""
import pytest

pytest.importorskip("OCP")

BASE = ["face-gear", "--module", "2", "--tolerance", "1", "--step", "brep"]


def _read_back(path):
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    rd = STEPControl_Reader()
    assert rd.ReadFile(str(path)) == IFSelect_RetDone
    rd.TransferRoots()
    shape = rd.OneShape()
    ex, n = TopExp_Explorer(shape, TopAbs_SOLID), 0
    while ex.More():
        n += 1
        ex.Next()
    return n, BRepCheck_Analyzer(shape).IsValid()


@pytest.mark.parametrize("z2, z0, r2", [(30, 15, "35.3849"), (40, 20, "46.3845")])
def test_pointed_tip_brep_at_coarse_tolerance(tmp_path, capsys, z2, z0, r2):
    from gear3d.cli import main
    out = tmp_path / "f.step"
    rc = main(BASE + ["--teeth", str(z2), "--shaper-teeth", str(z0), "--outer-radius", r2, "-o", str(out)])
    err = capsys.readouterr().err
    assert rc == 0, err            # 40/20: a tip land of 2.6e-7 mm, below the sewing tolerance, closed
    assert _read_back(out) == (1, True)
