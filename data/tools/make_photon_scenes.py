#!/usr/bin/env python3
"""Writes the photon-mapping test scenes (docs/photon-mapping.md). Run from data/.
- point-light-plane.json: a 1 mm square lamp facing down 1 m above a black 40 m plane.
- mirror-spot.json: a small lamp, a 45-degree mirror and a black wall with a grey target
  inside the mirror's reflected spot; the geometry of the expected irradiance is in the docs.
- cornell-box-specular.json: the Cornell box with a glass short block and a mirror tall block."""
import json

def dump(name, scene):
    with open(name, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")

def square_z(cx, cy, z, half, up):
    """Axis-aligned square in the plane z, facing +z when up else -z (CCW from the front)."""
    a, b, c, d = (cx - half, cy - half, z), (cx + half, cy - half, z), (cx + half, cy + half, z), (cx - half, cy + half, z)
    return [list(p) for p in ((a, b, c, d) if up else (a, d, c, b))]

# ---- Point light over a plane. Lamp side s = 1 mm, E = 1e6 W/m2: power 1 W, h = 1 m.
dump("point-light-plane.json", {
    "name": "point-light-plane",
    "description": "A 1 mm square Lambertian lamp (power 1 W) facing down at h = 1 m over a black 40 m x 40 m "
                   "plane: E(x) = (Phi/pi) h^2/(h^2 + x^2)^2 on the plane (docs/photon-mapping.md).",
    "units": "m",
    "materials": {"black": {"reflectance": [0, 0, 0]},
                  "lamp": {"reflectance": [0, 0, 0], "emission": [1e6, 1e6, 1e6]}},
    "surfaces": [{"name": "plane", "material": "black", "polygon": square_z(0, 0, 0, 20, True)},
                 {"name": "lamp", "material": "lamp", "polygon": square_z(0, 0, 1, 0.0005, False)}],
    "camera": {"position": [0, -6, 4], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov_deg": 50}})

# ---- Mirror spot. Lamp (side 1 cm, power 1 W) at (0, 0, 1) facing down; a 0.2 m mirror
# tilted 45 degrees (normal (-1, 0, 1)/sqrt 2) centred at (0, 0, 0.4) sends its light toward -x;
# the wall x = -1 (facing +x, black) has a grey 0.1 m target centred at (-1, 0, 0.4).
def wall_x(x, y0, y1, z0, z1):
    return [[x, y0, z0], [x, y1, z0], [x, y1, z1], [x, y0, z1]]  # faces +x

r2 = 0.1 / 2 ** 0.5
mirror = [[-r2, -0.1, 0.4 - r2], [r2, -0.1, 0.4 + r2], [r2, 0.1, 0.4 + r2], [-r2, 0.1, 0.4 - r2]]
dump("mirror-spot.json", {
    "name": "mirror-spot",
    "description": "A 1 cm lamp (1 W) facing down at (0,0,1), a 45-degree mirror (reflectance 0.9) at (0,0,0.4) and "
                   "a black wall at x = -1 with a grey target inside the reflected spot. The target's irradiance is "
                   "the lamp's plus the mirror image's (docs/photon-mapping.md); radiosity sees only the first.",
    "units": "m",
    "materials": {"black": {"reflectance": [0, 0, 0]},
                  "grey": {"reflectance": [0.5, 0.5, 0.5]},
                  "mirror": {"brdf": "mirror", "specular": [0.9, 0.9, 0.9]},
                  "lamp": {"reflectance": [0, 0, 0], "emission": [1e4, 1e4, 1e4]}},
    "surfaces": [
        {"name": "lamp", "material": "lamp", "polygon": square_z(0, 0, 1, 0.005, False)},
        {"name": "mirror", "material": "mirror", "polygon": mirror},
        {"name": "target", "material": "grey", "polygon": wall_x(-1, -0.05, 0.05, 0.35, 0.45)},
        {"name": "wall", "material": "black", "polygons": [
            wall_x(-1, -1, 1, 0, 0.35), wall_x(-1, -1, 1, 0.45, 1.2),
            wall_x(-1, -1, -0.05, 0.35, 0.45), wall_x(-1, 0.05, 1, 0.35, 0.45)]}],
    "camera": {"position": [1.5, -1.2, 1.0], "look_at": [-0.6, 0, 0.4], "up": [0, 0, 1], "fov_deg": 45}})

# ---- Cornell box with specular blocks.
box = json.load(open("cornell-box.json"))
box["name"] = "cornell-box-specular"
box["description"] = "The Cornell box with a glass (ior 1.5) short block and a mirror tall block: caustics."
box["materials"]["glass"] = {"brdf": "glass", "ior": 1.5}
box["materials"]["mirror"] = {"brdf": "mirror"}
for s in box["surfaces"]:
    if s["name"] == "short block":
        s["material"] = "glass"
    if s["name"] == "tall block":
        s["material"] = "mirror"
dump("cornell-box-specular.json", box)
