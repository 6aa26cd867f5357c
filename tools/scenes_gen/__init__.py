"""The scenes that tools/make_scenes.py writes: one module per scene, built from the glTF writer
(gltf), meshes (mesh), textures (texture), neon lettering (neon) and vector maths (vec).

SCENES maps each scene's folder name to its builder, which returns (Gltf, title, samples per pixel).
"""
from .courtyard import courtyard
from .gradient_screen import gradient_screen
from .lantern import lantern
from .mosaic import mosaic
from .neon_sign import neon_sign
from .night_street import night_street
from .tile_emitter import tile_emitter
from .video_wall import video_wall

SCENES = {"neon-sign": neon_sign, "gradient-screen": gradient_screen, "mosaic": mosaic,
          "tile-emitter": tile_emitter, "lantern": lantern, "night-street": night_street,
          "video-wall": video_wall, "courtyard": courtyard}
