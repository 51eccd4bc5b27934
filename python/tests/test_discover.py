"""matforge.discover: sets, their files, each role's file with the rule and evidence that decided it,
the same choice the full run makes (validate's inputs), and the vendors' names as they mean them."""

from __future__ import annotations

import matforge
import pytest
from conftest import set_paths

SETS = ["ambientcg_OfficeCeiling005_1K-JPG", "flat_folder_two_sets", "godot_tps-demo_container1",
        "polyhaven_broken_wall_1k_jpg+webp"]


def test_discovery_chooses_what_the_run_reads(corpus):
    inputs = set_paths(corpus, SETS)
    d = matforge.discover(inputs)
    v = matforge.validate(inputs)
    assert sorted(s.name for s in d.sets) == sorted(m.name for m in v.materials)
    assert len(d.sets) == 5 and not d.failures
    for s in d.sets:
        m = v.material(s.name)
        assert s.convention == m.convention
        assert s.maps and set(s.roles) <= {i.role for i in m.inputs}, s.name
        for choice in s.maps:
            i = m.input(choice.role)
            assert (choice.file, choice.rule, choice.family) == (i.file, i.rule, i.family), (s.name, i.role)
            assert (choice.width, choice.height, choice.channels, choice.bit_depth) == (
                i.width, i.height, i.channels, i.bit_depth)
        assert set(s.roles.values()) <= set(s.files)


def test_vendor_names_and_evidence(corpus):
    d = matforge.discover(set_paths(corpus, SETS))
    office = d["OfficeCeiling005"]
    assert office.source.endswith("ambientcg_OfficeCeiling005_1K-JPG")
    assert "OfficeCeiling005_1K-JPG_NormalDX.jpg" in office.files
    normal = next(m for m in office.maps if m.role == "normal")
    # Both conventions ship; the preset's (gltf: +Y) is chosen, the other kept as a rejected candidate.
    assert normal.file == "OfficeCeiling005_1K-JPG_NormalGL.jpg" and normal.normal_convention == "gl"
    assert [r.file for r in normal.rejected] == ["OfficeCeiling005_1K-JPG_NormalDX.jpg"]
    assert normal.rejected[0].normal_convention == "dx"
    assert office.role_of("OfficeCeiling005_1K-JPG_Roughness.jpg") == "roughness"
    assert office.roles["metalness"] == "OfficeCeiling005_1K-JPG_Metalness.jpg"
    assert office.roles["emissive"] == "OfficeCeiling005_1K-JPG_Emission.jpg"
    assert all(m.rule.startswith("ambientcg:") for m in office.maps), [m.rule for m in office.maps]
    # The set's MaterialX document agrees on the role: it is the evidence, beside the name.
    assert normal.evidence == "OfficeCeiling005_1K-JPG.mtlx" and "mtlx:" in normal.rule
    assert normal.width == 1024 and normal.bit_depth == 8
    assert d["container1"].maps[0].evidence == "name"
    # With the dx preset, the other file.
    dx = matforge.discover(set_paths(corpus, SETS[:1]), preset="unreal")
    assert dx.sets[0].roles["normal"] == "OfficeCeiling005_1K-JPG_NormalDX.jpg"
    # Godot's packed map is the ORM input; the flat folder splits into its two materials.
    assert d["container1"].roles == {"albedo": "container1_albedo.png", "normal": "container1_normal.png",
                                      "orm": "container1_orm.png"}
    flat = sorted(s.name for s in d.sets if s.root.endswith("flat_folder_two_sets"))
    assert flat == ["Rocks004", "Surface_Imperfection_001"]
    unrecognized = [f for f in d["Rocks004"].findings + d["Surface_Imperfection_001"].findings
                    if f.code == "UNRECOGNIZED_FILE"]
    assert [f.file for f in unrecognized] == ["Material_1586.jpg"]  # a vendor's preview render


def test_rules_exclusions_apply(corpus):
    one = set_paths(corpus, ["ambientcg_OfficeCeiling005_1K-JPG"])
    d = matforge.discover(one, rules={"exclude": [{"file": "*_Emission.jpg", "reason": "not wanted"}]})
    s = d.sets[0]
    assert "emissive" not in s.roles
    excluded = [f for f in s.findings if f.file == "OfficeCeiling005_1K-JPG_Emission.jpg"]
    assert [f.code for f in excluded] == ["UNRECOGNIZED_FILE"] and "not wanted" in excluded[0].message


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__]))
