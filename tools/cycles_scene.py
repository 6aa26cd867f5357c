"""Runs inside Blender (3.4): imports a glTF file with Blender's glTF importer, sets its materials
as tools/cycles_compare.py's docstring says (the glTF material as its specification defines it,
as far as Cycles can render it, or Lambertian with --diffuse) and renders it with Cycles.

  blender -b --factory-startup --python tools/cycles_scene.py -- '{"scene": ..., "out": ...}'

The one argument is a JSON object: scene, out (EXR), width, height, spp, bounces, diffuse
(bool), transmission ("gltf": thin surfaces let light through unbent; "importer": as the
importer leaves them, refracting), seed, time_limit (seconds, 0 for none).
"""
import json
import math
import sys

import numpy

numpy.bool = bool  # Blender 3.4's glTF importer calls numpy.bool, gone from Debian's numpy
import bpy  # noqa: E402

SMOOTH_ALPHA = 1e-3  # trs-render's kMinAlpha: a thin surface smoother than roughness^2 < this passes light straight
COAT_F0 = 0.04  # glTF's clear coat: an index of refraction of 1.5
WHITE = (1.0, 1.0, 1.0, 1.0)


# --- The glTF material of each Blender material -------------------------------------------------

def record_extensions():
    """Makes the importer store each material's glTF extensions (JSON) in the Blender material's
    "gltf_extensions" property: what it does not turn into nodes, or turns into something else."""
    from io_scene_gltf2.blender.imp import gltf2_blender_material
    create = gltf2_blender_material.BlenderMaterial.create

    def create_and_record(gltf, material_index, vertex_color):
        source = gltf.data.materials[material_index]
        extensions = json.dumps(source.extensions or {})  # before the importer appends alpha to its colours
        create(gltf, material_index, vertex_color)
        bpy.data.materials[source.blender_material[vertex_color]]["gltf_extensions"] = extensions
    gltf2_blender_material.BlenderMaterial.create = staticmethod(create_and_record)


def extensions_of(material):
    return json.loads(material.get("gltf_extensions", "{}"))


def luminance(c):
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]


def dielectric_f0(extensions):
    """The dielectric layer's reflectance at normal incidence (its largest channel) and at grazing
    incidence, as KHR_materials_ior and _specular define them (and trs-render reads them)."""
    ior = extensions.get("KHR_materials_ior", {}).get("ior", 1.5)
    f0_ior = 1.0 if ior == 0 else ((ior - 1) / (ior + 1)) ** 2
    specular = extensions.get("KHR_materials_specular", {})
    weight = specular.get("specularFactor", 1.0)
    colour = specular.get("specularColorFactor", [1.0, 1.0, 1.0])
    f0 = [min(f0_ior * c, 1.0) * weight for c in colour]
    return f0, weight


def thin_walled(extensions):
    return extensions.get("KHR_materials_volume", {}).get("thicknessFactor", 0.0) <= 0.0


# --- Node building ------------------------------------------------------------------------------

class Nodes:
    """Builds on one material's node tree. A value is an output socket or a constant."""

    def __init__(self, tree):
        self.tree = tree

    def new(self, kind, **properties):
        node = self.tree.nodes.new(kind)
        for key, value in properties.items():
            setattr(node, key, value)
        return node

    def feed(self, value, socket):
        if isinstance(value, bpy.types.NodeSocket):
            self.tree.links.new(value, socket)
        elif value is not None:
            socket.default_value = value

    def take(self, socket, reset=None):
        """What drives an input: the socket linked to it, else its value; with `reset`, the input
        is unlinked and set to `reset`."""
        if socket.is_linked:
            value = socket.links[0].from_socket
        elif hasattr(socket.default_value, "__len__"):
            value = tuple(socket.default_value)
        else:
            value = float(socket.default_value)
        if reset is not None:
            for link in list(socket.links):
                self.tree.links.remove(link)
            socket.default_value = reset
        return value

    def math(self, operation, a, b=0.0, c=None):
        if not isinstance(a, bpy.types.NodeSocket) and not isinstance(b, bpy.types.NodeSocket) and c is None:
            return {"MULTIPLY": a * b, "ADD": a + b, "SUBTRACT": a - b, "MAXIMUM": max(a, b),
                    "LESS_THAN": float(a < b), "POWER": a ** b}[operation]
        node = self.new("ShaderNodeMath", operation=operation)
        for value, socket in zip((a, b, c), node.inputs):
            self.feed(value, socket)
        return node.outputs[0]

    def bsdf(self, kind, normal=None, **inputs):
        node = self.new(kind)
        if "distribution" in inputs:
            node.distribution = inputs.pop("distribution")
        for name, value in inputs.items():
            self.feed(value, node.inputs[name])
        if normal is not None:
            self.feed(normal, node.inputs["Normal"])
        return node.outputs[0]

    def mix(self, fac, first, second):
        """(1 - fac) first + fac second; a shader None is black."""
        node = self.new("ShaderNodeMixShader")
        self.feed(fac, node.inputs[0])
        for shader, socket in ((first, node.inputs[1]), (second, node.inputs[2])):
            if shader is not None:
                self.tree.links.new(shader, socket)
        return node.outputs[0]

    def add(self, first, second):
        node = self.new("ShaderNodeAddShader")
        self.tree.links.new(first, node.inputs[0])
        self.tree.links.new(second, node.inputs[1])
        return node.outputs[0]

    def facing(self, normal=None):
        """1 - |N.V|: the Layer Weight node's Facing at blend 0.5."""
        node = self.new("ShaderNodeLayerWeight")
        node.inputs["Blend"].default_value = 0.5
        self.feed(normal, node.inputs["Normal"])
        return node.outputs["Facing"]

    def schlick(self, f0, f90, normal=None):
        """f0 + (f90 - f0) (1 - |N.V|)^5: glTF's Fresnel, at the microfacet normal of a smooth surface."""
        return self.math("MULTIPLY_ADD", self.math("POWER", self.facing(normal), 5.0), f90 - f0, f0)

    def curve(self, normal, values):
        """A function of |N.V| given at len(values) evenly spaced points of 1 - |N.V| (a Float Curve)."""
        node = self.new("ShaderNodeFloatCurve")
        self.feed(self.facing(normal), node.inputs["Value"])
        points = node.mapping.curves[0].points
        top = max(max(values), 1e-6)
        while len(points) < len(values):
            points.new(0.0, 0.0)
        for point, (k, value) in zip(points, enumerate(values)):
            point.location = (k / (len(values) - 1), value / top)
        node.mapping.update()
        return self.math("MULTIPLY", node.outputs["Value"], top)

    def max_component(self, colour):
        if not isinstance(colour, bpy.types.NodeSocket):
            return max(colour[:3])
        split = self.new("ShaderNodeSeparateColor")
        self.feed(colour, split.inputs[0])
        return self.math("MAXIMUM", self.math("MAXIMUM", split.outputs[0], split.outputs[1]), split.outputs[2])


def principled_of(material):
    """The importer's Principled BSDF and Material Output, or (None, None) where it made others."""
    if not material.use_nodes:
        return None, None
    tree = material.node_tree
    principled = next((n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    output = next((n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"), None)
    return (principled, output) if principled and output else (None, None)


# --- Sheen: Charlie's albedo, and the Velvet BSDF scaled to it ------------------------------------

def sheen_lambda(mu, alpha):
    """The Charlie sheen's Lambda, Conty and Kulla's fit (trs-render's tracer/src/sheen.cpp)."""
    t = (1 - alpha) ** 2
    a, b, c = 21.5473 + (25.3245 - 21.5473) * t, 3.82987 + (3.32435 - 3.82987) * t, 0.19823 + (0.16801 - 0.19823) * t
    d, e = -1.97760 + (-1.27393 + 1.97760) * t, -4.32054 + (-4.85967 + 4.32054) * t

    def fit(x):
        return a / (1 + b * numpy.power(x, c)) + d * x + e
    mu = numpy.abs(mu)
    return numpy.where(mu < 0.5, numpy.exp(fit(mu)), numpy.exp(2 * fit(0.5) - fit(1 - mu)))


def directional_albedo(f_cos, mu, n=96):
    """The integral of f(wo, wi) |cos wi| over the hemisphere of wi, wo at cosine mu (midpoints in
    cos theta_i and phi)."""
    cos_i = (numpy.arange(n) + 0.5) / n
    phi = (numpy.arange(2 * n) + 0.5) / (2 * n) * 2 * math.pi
    ci, ph = numpy.meshgrid(cos_i, phi, indexing="ij")
    si = numpy.sqrt(1 - ci * ci)
    wi = numpy.stack([si * numpy.cos(ph), si * numpy.sin(ph), ci], -1)
    wo = numpy.array([math.sqrt(max(0.0, 1 - mu * mu)), 0.0, mu])
    return float(f_cos(wo, wi).mean() * 2 * math.pi)


def charlie_f_cos(roughness):
    alpha = max(roughness * roughness, 1e-3)

    def f_cos(wo, wi):
        h = wo + wi
        cos_h = h[..., 2] / numpy.linalg.norm(h, axis=-1)
        d = (2 + 1 / alpha) * numpy.power(numpy.maximum(1 - cos_h ** 2, 0), 0.5 / alpha) / (2 * math.pi)
        return d / (4 * (1 + sheen_lambda(wo[2], alpha) + sheen_lambda(wi[..., 2], alpha)) * wo[2])
    return f_cos


def velvet_f_cos(sigma):
    """Cycles' Velvet BSDF (Ashikhmin), as Cycles 3.4 evaluates it: f |cos wi|."""
    inv_sigma2 = 1 / max(min(sigma, 1.0), 0.01) ** 2

    def f_cos(wo, wi):
        h = wo + wi
        h = h / numpy.linalg.norm(h, axis=-1, keepdims=True)
        cos_nh, cos_ho = h[..., 2], numpy.abs(h @ wo)
        ratio = numpy.maximum(cos_nh / cos_ho, 1e-5)
        g = numpy.minimum(1, numpy.minimum(2 * ratio * wo[2], 2 * ratio * wi[..., 2]))
        sin2 = numpy.maximum(1 - cos_nh ** 2, 1e-12)
        d = numpy.exp(-cos_nh ** 2 / sin2 * inv_sigma2) * inv_sigma2 / math.pi / sin2 ** 2
        return numpy.where(numpy.abs(cos_nh) < 1 - 1e-5, 0.25 * d * g / wo[2], 0.0)
    return f_cos


def sheen_tables(roughness, sigma, points=17):
    """At `points` values of 1 - |N.V| from 0 to 1: Charlie's directional albedo, and the factor
    that brings the Velvet BSDF of `sigma` to it."""
    charlie, velvet = [], []
    for k in range(points):
        mu = max(1 - k / (points - 1), 0.02)
        charlie.append(min(directional_albedo(charlie_f_cos(roughness), mu), 1.0))
        velvet.append(directional_albedo(velvet_f_cos(sigma), mu))
    return charlie, [c / max(v, 1e-4) for c, v in zip(charlie, velvet)]


# --- The materials ------------------------------------------------------------------------------

def cut_mask(material):
    """glTF's MASK in the shader: the importer's alpha, cut at the material's alphaCutoff (its
    Eevee alpha_threshold) as glTF cuts it, opaque where alpha >= cutoff."""
    principled, _ = principled_of(material)
    if principled is None or getattr(material, "blend_method", None) != "CLIP":
        return
    nodes = Nodes(material.node_tree)
    alpha = nodes.take(principled.inputs["Alpha"])
    nodes.feed(nodes.math("SUBTRACT", 1.0, nodes.math("LESS_THAN", alpha, material.alpha_threshold)),
               principled.inputs["Alpha"])


def fix_colour_mixes(material):
    """Blender 3.4's importer multiplies a texture by a colour factor (emissiveFactor that is not
    grey, sheenColorFactor) with a Mix node of RGBA data but links the node's float Result, which
    is 0: such an emitter would be black. Relinks its colour Result."""
    tree = material.node_tree
    for link in list(tree.links):
        node = link.from_node
        if node.type == "MIX" and node.data_type == "RGBA" and link.from_socket == node.outputs[0]:
            target = link.to_socket
            tree.links.remove(link)
            tree.links.new(node.outputs[2], target)


def front_emission(material):
    """glTF's single-sided emitter (doubleSided false, the importer's Backface Culling, which only
    Eevee reads) emits from its front face alone, as trs-render's do: the Principled BSDF's
    Emission Strength times 1 - Backfacing. Cycles emits from both faces: a panel 2 cm before a
    wall would light the wall behind it and, round its edges, the room."""
    principled, _ = principled_of(material)
    if principled is None or not material.use_backface_culling:
        return
    nodes = Nodes(material.node_tree)
    strength = nodes.take(principled.inputs["Emission Strength"])
    front = nodes.math("SUBTRACT", 1.0, nodes.new("ShaderNodeNewGeometry").outputs["Backfacing"])
    nodes.feed(nodes.math("MULTIPLY", strength, front), principled.inputs["Emission Strength"])


def fix_absorption(material, extensions):
    """KHR_materials_volume's absorption: transmittance attenuationColor^(d / attenuationDistance),
    an absorption coefficient -ln(c) / distance per channel. The importer writes 1 / distance as
    the Volume Absorption's density and c as its colour, which Cycles reads as (1 - c) / distance."""
    volume = extensions.get("KHR_materials_volume", {})
    node = next((n for n in material.node_tree.nodes if n.type == "VOLUME_ABSORPTION"), None)
    if node is None or "attenuationDistance" not in volume:
        return
    colour = volume.get("attenuationColor", [1.0, 1.0, 1.0])
    sigma = [-math.log(max(c, 1e-6)) / volume["attenuationDistance"] for c in colour]
    density = max(sigma)
    node.inputs["Density"].default_value = density
    node.inputs["Color"].default_value = [1 - s / density if density > 0 else 1.0 for s in sigma] + [1.0]


def specular_textured(extensions):
    specular = extensions.get("KHR_materials_specular", {})
    return "specularTexture" in specular or "specularColorTexture" in specular


def fix_specular(principled, extensions):
    """Where KHR_materials_specular has textures, the importer's baked Specular image times
    specularFactor, which its conversion leaves out (a file's factors alone: specular_layer())."""
    socket = principled.inputs["Specular"]
    if specular_textured(extensions) and socket.is_linked:
        nodes = Nodes(socket.node.id_data)
        factor = extensions["KHR_materials_specular"].get("specularFactor", 1.0)
        nodes.feed(nodes.math("MULTIPLY", nodes.take(socket), factor), socket)


def specular_layer(nodes, principled, extensions, normal, share):
    """The dielectric specular layer of KHR_materials_ior and _specular in place of the Principled
    BSDF's (whose Specular is set to 0): a GGX Glossy BSDF of the layer's Schlick Fresnel, f0 =
    min(f0(ior) specularColor, 1) specularFactor and f90 = specularFactor, coloured, added as the
    Principled BSDF adds its own, times 1 - metallic and `share` (what refraction leaves: the
    Principled BSDF's glass reflects with its own Fresnel at the IOR). The Principled BSDF takes
    one grey F0 (Specular, 0.08 F0 at 1) rising to 1 at grazing, and tints it only towards the base
    colour; the importer converts ior for a file with KHR_materials_specular alone, without
    specularFactor."""
    f0, f90 = dielectric_f0(extensions)
    nodes.take(principled.inputs["Specular"], reset=0.0)
    fresnel = nodes.new("ShaderNodeMix", data_type="RGBA", blend_type="MIX")
    nodes.feed(nodes.math("POWER", nodes.facing(normal), 5.0), fresnel.inputs["Factor"])
    nodes.feed(tuple(f0) + (1.0,), fresnel.inputs[6])
    nodes.feed((f90, f90, f90, 1.0), fresnel.inputs[7])
    glossy = nodes.bsdf("ShaderNodeBsdfGlossy", normal, distribution="GGX", Color=fresnel.outputs[2],
                        Roughness=nodes.take(principled.inputs["Roughness"]))
    weight = nodes.math("MULTIPLY", nodes.math("SUBTRACT", 1.0, nodes.take(principled.inputs["Metallic"])), share)
    return nodes.mix(weight, None, glossy)


def transmission_bsdf(nodes, extensions, base, roughness, normal, ior, mode):
    """What a transmissive surface lets through. Thin (no volume) in "gltf" mode: a Transparent
    BSDF of the base colour where it is smooth (light straight through, as the file means), a
    Translucent BSDF where rough (Cycles 3.4 has no GGX lobe mirrored through the surface); a
    volume's boundary, or any surface in "importer" mode, refracts (Refraction BSDF)."""
    if thin_walled(extensions) and mode == "gltf":
        smooth = nodes.math("LESS_THAN", nodes.math("MULTIPLY", roughness, roughness), SMOOTH_ALPHA)
        through = nodes.bsdf("ShaderNodeBsdfTransparent", Color=base)
        if smooth == 1.0:
            return through
        spread = nodes.bsdf("ShaderNodeBsdfTranslucent", normal, Color=base)
        return spread if smooth == 0.0 else nodes.mix(smooth, spread, through)
    return nodes.bsdf("ShaderNodeBsdfRefraction", normal, distribution="GGX", Color=base, Roughness=roughness,
                      IOR=ior)


def cover(nodes, surface, alpha):
    """Coverage as the Principled BSDF applies it: a Transparent BSDF where alpha < 1."""
    if isinstance(alpha, float) and alpha >= 1.0:
        return surface
    return nodes.mix(alpha, nodes.bsdf("ShaderNodeBsdfTransparent", Color=WHITE), surface)


def emission_of(nodes, principled):
    """The Principled BSDF's emission as an Emission node, taken out of it; None where black."""
    colour = nodes.take(principled.inputs["Emission"], reset=(0.0, 0.0, 0.0, 1.0))
    strength = nodes.take(principled.inputs["Emission Strength"], reset=0.0)
    if not isinstance(colour, bpy.types.NodeSocket) and max(colour[:3]) == 0 or strength == 0.0:
        return None
    return nodes.bsdf("ShaderNodeEmission", Color=colour, Strength=strength)


def diffuse_surface(material, extensions, mode):
    """--diffuse: a Lambertian Diffuse BSDF of the base colour and normal beside the material's
    transmission (mixed by its factor or texture), plus its emission, under its alpha; as
    trs-render's --diffuse-materials (no specular layer: the transmission without Fresnel)."""
    principled, output = principled_of(material)
    if principled is None:
        return
    nodes = Nodes(material.node_tree)
    inputs = principled.inputs
    base = nodes.take(inputs["Base Color"])
    normal = nodes.take(inputs["Normal"]) if inputs["Normal"].is_linked else None
    surface = nodes.bsdf("ShaderNodeBsdfDiffuse", normal, Color=base)
    transmission = nodes.take(inputs["Transmission"])
    if transmission != 0.0:
        through = transmission_bsdf(nodes, extensions, base, nodes.take(inputs["Roughness"]), normal,
                                    nodes.take(inputs["IOR"]), mode)
        surface = nodes.mix(transmission, surface, through)
    emission = emission_of(nodes, principled)
    if emission is not None:
        surface = nodes.add(surface, emission)
    nodes.feed(cover(nodes, surface, nodes.take(inputs["Alpha"])), output.inputs["Surface"])


def gltf_surface(material, extensions, mode):
    """The glTF material where the Principled BSDF alone cannot hold it: the specular layer of
    KHR_materials_ior and _specular (specular_layer()), thin transmission (a pane of glTF's thin
    dielectric: Schlick's F between transmission_bsdf() and a GGX reflection), the clear coat (a
    GGX coat of F0 0.04 over the rest, which it dims, emission included, by 1 - clearcoat F;
    Cycles' own Clearcoat is Disney's, a GTR1 lobe at a quarter of the weight, and leaves emission
    undimmed) and the sheen (the importer's Velvet BSDF of the sheen colour, scaled to Charlie's
    directional albedo, over the rest dimmed by 1 - max(sheenColor) times that albedo). The
    Principled BSDF keeps the diffuse, metal and its specular layer otherwise (and a volume's
    refraction)."""
    principled, output = principled_of(material)
    if principled is None:
        return
    tree = material.node_tree
    nodes = Nodes(tree)
    inputs = principled.inputs
    thin = thin_walled(extensions) and mode == "gltf"
    coat = "KHR_materials_clearcoat" in extensions
    velvet = next((n for n in tree.nodes if n.type == "BSDF_VELVET"), None)
    layer = ("KHR_materials_ior" in extensions or "KHR_materials_specular" in extensions) \
        and not specular_textured(extensions)
    if not ((thin and (inputs["Transmission"].is_linked or inputs["Transmission"].default_value > 0))
            or coat or velvet is not None or layer):
        return
    alpha = nodes.take(inputs["Alpha"], reset=1.0)
    emission = emission_of(nodes, principled)
    normal = nodes.take(inputs["Normal"]) if inputs["Normal"].is_linked else None
    metallic = nodes.take(inputs["Metallic"])
    # A thin surface's transmission leaves the Principled BSDF for the pane below; a volume's
    # stays, refracting, and the specular layer takes the share it leaves.
    transmission = nodes.take(inputs["Transmission"], reset=0.0 if thin else None)
    surface = principled.outputs["BSDF"]
    if layer:
        kept = 0.0 if thin else transmission
        surface = nodes.add(surface, specular_layer(nodes, principled, extensions, normal,
                                                    nodes.math("SUBTRACT", 1.0, kept)))
    if thin and transmission != 0.0:
        roughness = nodes.take(inputs["Roughness"])
        base = nodes.take(inputs["Base Color"])
        through = transmission_bsdf(nodes, extensions, base, roughness, normal, None, mode)
        f0, f90 = dielectric_f0(extensions)
        reflection = nodes.bsdf("ShaderNodeBsdfGlossy", normal, distribution="GGX", Color=WHITE,
                                Roughness=roughness)
        pane = nodes.mix(nodes.schlick(max(f0), f90, normal), through, reflection)
        share = nodes.math("MULTIPLY", transmission, nodes.math("SUBTRACT", 1.0, metallic))
        surface = nodes.mix(share, surface, pane)
    if velvet is not None:
        sheen = extensions.get("KHR_materials_sheen", {})
        colour = nodes.take(velvet.inputs["Color"])
        sigma = velvet.inputs["Sigma"].default_value
        charlie, scale = sheen_tables(sheen.get("sheenRoughnessFactor", 0.0), sigma)
        normal = nodes.take(inputs["Normal"]) if inputs["Normal"].is_linked else None
        nodes.feed(normal, velvet.inputs["Normal"])
        scaled = nodes.new("ShaderNodeMix", data_type="RGBA", blend_type="MULTIPLY")
        scaled.inputs["Factor"].default_value = 1.0
        nodes.feed(colour, scaled.inputs[6])
        nodes.feed(nodes.curve(normal, scale), scaled.inputs[7])
        nodes.feed(scaled.outputs[2], velvet.inputs["Color"])
        albedo = nodes.math("MULTIPLY", nodes.max_component(colour), nodes.curve(normal, charlie))
        surface = nodes.add(nodes.mix(nodes.math("SUBTRACT", 1.0, albedo), None, surface), velvet.outputs["BSDF"])
    if emission is not None:
        surface = nodes.add(surface, emission)
    if coat:
        weight = nodes.take(inputs["Clearcoat"], reset=0.0)
        roughness = nodes.take(inputs["Clearcoat Roughness"])
        normal = nodes.take(inputs["Clearcoat Normal"]) if inputs["Clearcoat Normal"].is_linked else None
        coat_layer = nodes.bsdf("ShaderNodeBsdfGlossy", normal, distribution="GGX", Color=WHITE,
                                Roughness=roughness)
        surface = nodes.mix(nodes.math("MULTIPLY", weight, nodes.schlick(COAT_F0, 1.0, normal)), surface, coat_layer)
    nodes.feed(cover(nodes, surface, alpha), output.inputs["Surface"])


def set_materials(diffuse, mode):
    for material in bpy.data.materials:
        principled, _ = principled_of(material)
        if principled is None:
            continue
        extensions = extensions_of(material)
        fix_colour_mixes(material)
        cut_mask(material)
        front_emission(material)
        fix_absorption(material, extensions)
        if diffuse:
            diffuse_surface(material, extensions, mode)
        else:
            fix_specular(principled, extensions)
            gltf_surface(material, extensions, mode)


# --- The render ---------------------------------------------------------------------------------

def main():
    options = json.loads(sys.argv[sys.argv.index("--") + 1])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    record_extensions()
    bpy.ops.import_scene.gltf(filepath=options["scene"], convert_lighting_mode="SPEC")
    scene = bpy.context.scene
    set_materials(options["diffuse"], options.get("transmission", "gltf"))
    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    if not cameras:
        sys.exit("cycles_scene: the file has no camera")
    scene.camera = cameras[0]
    for light in bpy.data.lights:
        light.shadow_soft_size = 0.0
        if light.type == "SUN":
            light.angle = 0.0
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    render = scene.render
    render.engine = "CYCLES"
    render.resolution_x, render.resolution_y, render.resolution_percentage = options["width"], options["height"], 100
    render.filter_size = 0.01  # a box of one pixel, as trs-render's jittered camera samples
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    render.image_settings.color_mode = "RGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = options["spp"]
    cycles.seed = options.get("seed", 0)
    cycles.time_limit = options.get("time_limit", 0.0)
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.max_bounces = options["bounces"]
    for prop in ("diffuse_bounces", "glossy_bounces", "transmission_bounces", "volume_bounces"):
        setattr(cycles, prop, options["bounces"])
    cycles.transparent_max_bounces = 64
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    cycles.blur_glossy = 0.0
    if "threads" in options:
        render.threads_mode = "FIXED"
        render.threads = options["threads"]
    render.filepath = options["out"]
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
