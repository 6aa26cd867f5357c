"""Variants of a .gltf file for comparisons: its JSON edited and written into another folder, beside
copies of the buffers and images it names (relative URIs), so that the variant loads as the file
does and the source folder stays untouched."""
import json
import shutil
from pathlib import Path


def read(scene):
    """The JSON document of a .gltf file."""
    return json.loads(Path(scene).read_text())


def write(doc, scene, folder, name):
    """Writes `doc`, a variant of glTF file `scene`, as folder/name.gltf with copies of the files
    its buffers and images name; returns its path."""
    scene, folder = Path(scene), Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for entry in doc.get("buffers", []) + doc.get("images", []):
        uri = entry.get("uri", "")
        if uri and not uri.startswith("data:"):
            (folder / uri).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(scene.parent / uri, folder / uri)
    path = folder / f"{name}.gltf"
    path.write_text(json.dumps(doc, indent=1) + "\n")
    return path


def without_extensions(doc, extensions):
    """`doc` with `extensions` taken out of every material and of extensionsUsed/Required."""
    for material in doc.get("materials", []):
        for extension in extensions:
            material.get("extensions", {}).pop(extension, None)
    for key in ("extensionsUsed", "extensionsRequired"):
        if key in doc:
            doc[key] = [e for e in doc[key] if e not in extensions]
    return doc


def without_nodes(doc, names):
    """`doc` with the meshes of the nodes named taken away (the nodes stay, empty)."""
    for node in doc["nodes"]:
        if node.get("name") in names:
            node.pop("mesh", None)
    return doc
