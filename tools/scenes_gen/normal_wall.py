"""Scene normal-wall (materials): tangent-space normal maps under a low sun. A stone wall with
TANGENT given and a cobbled yard with none (tangents from the UVs), its map repeated by
KHR_texture_transform; the right half of each is mirrored (handedness -1)."""
from .gltf import MATERIALS_GENERATOR, REPEAT, Gltf
from .mesh import Mesh
from .relief import cobbles, normal_map, stone_blocks
from .vec import axis


def normal_wall():
    """A 12 x 4 m wall of stone blocks (2 x 2 m per repeat of its 256 x 256 map, sampler REPEAT,
    normalTexture scale 1) before a 12 x 10 m cobbled yard (a 256 x 256 map of 4 x 4 cobbles,
    scaled 5 times by KHR_texture_transform: 2 m per repeat), under a sun (1,500 lux) from the
    left at 75 degrees from the wall's normal. Both are symmetric about x = 0: their right
    halves' UVs run right to left (the wall's with TANGENT w = -1; the yard's handedness is the
    renderer's to find from its UVs), so that both halves show their relief lit from the left.
    The file has no emitter: the sun alone lights it."""
    gltf = Gltf("normal-wall", MATERIALS_GENERATOR, extensions=())
    wall = Mesh()  # facing +z; one repeat of the map per 2 m
    wall.add_quad((-6.0, 4.0, -3.0), axis(0, 6.0), axis(1, -4.0), (0, 0, 1), uv=(0.0, 0.0, 3.0, 2.0))
    wall.add_quad((0.0, 4.0, -3.0), axis(0, 6.0), axis(1, -4.0), (0, 0, 1), uv=(3.0, 0.0, 0.0, 2.0))
    wall.add_tangents()
    stone = gltf.material("stone", (0.6, 0.5, 0.42))
    blocks = normal_map("stone-blocks-normal.png", 256, 256, stone_blocks(256))
    gltf.set_normal_texture(stone, gltf.texture_info(blocks, REPEAT))
    gltf.mesh("wall", wall, stone)

    ground = Mesh()  # the UVs' top-left at the far left corner; no TANGENT
    ground.add_quad((-6.0, 0.0, -3.0), axis(0, 6.0), axis(2, 10.0), (0, 1, 0), uv=(0.0, 0.0, 0.6, 1.0))
    ground.add_quad((0.0, 0.0, -3.0), axis(0, 6.0), axis(2, 10.0), (0, 1, 0), uv=(0.6, 0.0, 0.0, 1.0))
    paving = gltf.material("cobbles", (0.45, 0.43, 0.4))
    stones = normal_map("cobbles-normal.png", 256, 256, cobbles(256))
    gltf.set_normal_texture(paving, gltf.texture_info(stones, REPEAT, transform={"scale": [5.0, 5.0]}))
    gltf.mesh("ground", ground, paving)
    gltf.punctual_light("sun", "directional", 1500.0, (1.0, 0.93, 0.82), direction=(0.85, -0.45, -0.26),
                        required=False)
    gltf.camera((0.0, 1.7, 6.5), (0.0, 1.3, -1.0), 0.8)
    return gltf, "Normal wall", 16
