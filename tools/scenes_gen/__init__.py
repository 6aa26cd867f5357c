"""The scenes that tools/make_scenes.py writes: one module per scene, built from the glTF writer
(gltf), meshes (mesh), textures (texture), normal maps (relief), neon lettering (neon) and vector
maths (vec).

SCENES maps each scene's folder name to its builder, which returns (Gltf, title, samples per pixel);
MATERIAL_SCENES does the same for scenes/materials, which tools/make_material_scenes.py writes:
one material feature each (coverage, normal maps, texture transforms and wrap modes, and the
material extensions: transmission, volume, ior and specular, clearcoat, sheen, a lamp's shade).

tools/make_real_scenes.py, which stages others' assets, reads their accessors with gltf's
read_accessor and turns the nodes it adds (object, camera) with vec's quaternion and look_at.
"""
from .atlas_sign import atlas_sign
from .blend_glass import blend_glass
from .coated_panel import coated_panel
from .courtyard import courtyard
from .floor_lamp import floor_lamp
from .glass_panes import glass_panes
from .glass_volume import glass_volume
from .ior_specular import ior_specular
from .gradient_screen import gradient_screen
from .lantern import lantern
from .mosaic import mosaic
from .neon_sign import neon_sign
from .night_street import night_street
from .normal_wall import normal_wall
from .sheen_cloth import sheen_cloth
from .stained_lamp import stained_lamp
from .tile_emitter import tile_emitter
from .video_wall import video_wall

SCENES = {"neon-sign": neon_sign, "gradient-screen": gradient_screen, "mosaic": mosaic,
          "tile-emitter": tile_emitter, "lantern": lantern, "night-street": night_street,
          "video-wall": video_wall, "courtyard": courtyard}
MATERIAL_SCENES = {"stained-lamp": stained_lamp, "blend-glass": blend_glass, "normal-wall": normal_wall,
                   "atlas-sign": atlas_sign, "glass-panes": glass_panes, "glass-volume": glass_volume,
                   "ior-specular": ior_specular, "coated-panel": coated_panel, "sheen-cloth": sheen_cloth,
                   "floor-lamp": floor_lamp}
