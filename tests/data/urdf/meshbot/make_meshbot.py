"""Writes the meshes of meshbot.urdf (armkit's 3-D view fixture): a box in
binary STL, a prism in ASCII STL, a box in OBJ, a box in Collada (in
centimetres, Y up, with a material colour), and a broken STL.
Run from this folder: python3 make_meshbot.py"""
import struct

def box(sx, sy, sz, z0=0.0):
    """Vertices and triangles of a box centred on x, y, from z0 to z0 + sz."""
    v = [(x * sx / 2, y * sy / 2, z0 + (z + 1) * sz / 2) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return v, tris

def binary_stl(path, v, tris):
    with open(path, "wb") as f:
        f.write(b"meshbot".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0, 0, 0))
            for i in t:
                f.write(struct.pack("<3f", *v[i]))
            f.write(b"\0\0")

def ascii_stl(path, v, tris):
    with open(path, "w") as f:
        f.write("solid meshbot\n")
        for t in tris:
            f.write("facet normal 0 0 0\n outer loop\n")
            for i in t:
                f.write("  vertex %g %g %g\n" % v[i])
            f.write(" endloop\nendfacet\n")
        f.write("endsolid meshbot\n")

def obj(path, v, tris):
    with open(path, "w") as f:
        f.write("".join("v %g %g %g\n" % p for p in v))
        f.write("".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in tris))

def dae(path, v, tris):
    # Centimetres and Y up: the reader must scale by 0.01 and turn y onto z.
    cm = [(x * 100, z * 100, -y * 100) for x, y, z in v]
    floats = " ".join("%g %g %g" % p for p in cm)
    p = " ".join("%d %d %d" % t for t in tris)
    with open(path, "w") as f:
        f.write(f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Y_UP</up_axis></asset>
  <library_effects><effect id="blue-effect"><profile_COMMON><technique sid="common"><lambert>
    <diffuse><color sid="diffuse">0.2 0.4 0.9 1</color></diffuse></lambert></technique></profile_COMMON></effect></library_effects>
  <library_materials><material id="blue" name="blue"><instance_effect url="#blue-effect"/></material></library_materials>
  <library_geometries><geometry id="wrist" name="wrist"><mesh>
    <source id="wrist-positions"><float_array id="wrist-array" count="{3 * len(cm)}">{floats}</float_array>
      <technique_common><accessor source="#wrist-array" count="{len(cm)}" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <vertices id="wrist-vertices"><input semantic="POSITION" source="#wrist-positions"/></vertices>
    <triangles material="blue-material" count="{len(tris)}"><input semantic="VERTEX" source="#wrist-vertices" offset="0"/><p>{p}</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="wrist-node">
    <instance_geometry url="#wrist"><bind_material><technique_common>
      <instance_material symbol="blue-material" target="#blue"/></technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
""")

binary_stl("meshes/base.stl", *box(0.2, 0.2, 0.1))
ascii_stl("meshes/upper.stl", *box(0.06, 0.06, 0.4))
obj("meshes/fore.obj", *box(0.05, 0.05, 0.3))
dae("meshes/wrist.dae", *box(0.08, 0.08, 0.1))
with open("meshes/broken.stl", "w") as f:
    f.write("solid broken\nfacet normal 0 0 1\n outer loop\n  vertex 0 0\n")
