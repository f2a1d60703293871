"""A water material that reads seasynth's foam and normals.

Live, the foam coverage (0..1) and the unit normals are point attributes of the mesh
(`seasynth_foam`, `seasynth_normal`, object space, Z up), read by Attribute nodes; baked,
the same numbers come from the `foam.exr` and `normal.exr` sequences through the grid's
UVs. Deep water is a dark, glossy Principled BSDF (IOR 1.33) lightened towards the crests;
foam mixes in a rough white BSDF. The nodes work in Eevee and Cycles.
"""

import bpy

TAG = "seasynth_water"
DEEP = (0.002, 0.012, 0.022, 1.0)
CREST = (0.006, 0.045, 0.05, 1.0)


def _node(nodes, kind, name, location):
    n = nodes.get(name)
    if n is None:
        n = nodes.new(kind)
        n.name = name
        n.label = name
    n.location = location
    return n


def build(name):
    mat = bpy.data.materials.new(name)
    mat[TAG] = True
    mat.use_nodes = True
    mat.diffuse_color = DEEP
    nt = mat.node_tree
    nodes, links = nt.nodes, nt.links
    for n in list(nodes):
        nodes.remove(n)
    out = _node(nodes, "ShaderNodeOutputMaterial", "Output", (900, 0))
    water = _node(nodes, "ShaderNodeBsdfPrincipled", "Water", (300, 200))
    water.inputs["Roughness"].default_value = 0.04
    water.inputs["IOR"].default_value = 1.333
    water.inputs["Specular"].default_value = 0.5
    foam = _node(nodes, "ShaderNodeBsdfPrincipled", "Foam BSDF", (300, -400))
    foam.inputs["Base Color"].default_value = (0.85, 0.88, 0.9, 1.0)
    foam.inputs["Roughness"].default_value = 0.9
    mix = _node(nodes, "ShaderNodeMixShader", "Foam Mix", (700, 0))
    links.new(water.outputs["BSDF"], mix.inputs[1])
    links.new(foam.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], out.inputs["Surface"])
    # Crests lighter than troughs: world height mapped over ±3 m.
    geo = _node(nodes, "ShaderNodeNewGeometry", "Geometry", (-700, 450))
    sep = _node(nodes, "ShaderNodeSeparateXYZ", "Height", (-500, 450))
    rng = _node(nodes, "ShaderNodeMapRange", "Crest Range", (-300, 450))
    rng.inputs["From Min"].default_value = -3.0
    rng.inputs["From Max"].default_value = 3.0
    col = _node(nodes, "ShaderNodeMixRGB", "Water Colour", (-50, 450))
    col.inputs["Color1"].default_value = DEEP
    col.inputs["Color2"].default_value = CREST
    links.new(geo.outputs["Position"], sep.inputs["Vector"])
    links.new(sep.outputs["Z"], rng.inputs["Value"])
    links.new(rng.outputs["Result"], col.inputs["Fac"])
    links.new(col.outputs["Color"], water.inputs["Base Color"])
    # Foam coverage × amount, clamped to 0..1.
    fa = _node(nodes, "ShaderNodeAttribute", "Foam Attribute", (-500, 0))
    fa.attribute_type = "GEOMETRY"
    fa.attribute_name = "seasynth_foam"
    amt = _node(nodes, "ShaderNodeMath", "Foam Amount", (300, -150))
    amt.operation = "MULTIPLY"
    amt.use_clamp = True
    links.new(amt.outputs["Value"], mix.inputs["Fac"])
    # Normals: object space to world space.
    na = _node(nodes, "ShaderNodeAttribute", "Normal Attribute", (-500, -250))
    na.attribute_type = "GEOMETRY"
    na.attribute_name = "seasynth_normal"
    vt = _node(nodes, "ShaderNodeVectorTransform", "Normal to World", (0, -250))
    vt.vector_type = "NORMAL"
    vt.convert_from = "OBJECT"
    vt.convert_to = "WORLD"
    # Baked: the foam and normal sequences (images set by the bake).
    ft = _node(nodes, "ShaderNodeTexImage", "Foam Sequence", (-500, -550))
    nm = _node(nodes, "ShaderNodeTexImage", "Normal Sequence", (-500, -850))
    for t in (ft, nm):
        t.interpolation = "Linear"
        t.extension = "REPEAT"
    return mat


def material_of(obj):
    for slot in obj.material_slots:
        if slot.material is not None and slot.material.get(TAG):
            return slot.material
    return None


def assign(obj):
    mat = material_of(obj)
    if mat is None:
        mat = build("seasynth water")
        obj.data.materials.append(mat)
    update_for(obj)
    return mat


def _unlink_input(nt, socket):
    for link in list(socket.links):
        nt.links.remove(link)


def update_for(obj):
    """Links the foam and normal sources for the object's mode and settings."""
    mat = material_of(obj)
    if mat is None or not mat.use_nodes:
        return
    s = obj.seasynth
    nt = mat.node_tree
    nodes, links = nt.nodes, nt.links
    need = ("Foam Amount", "Foam Attribute", "Normal Attribute", "Normal to World", "Water", "Foam BSDF")
    if any(nodes.get(n) is None for n in need):
        return  # the artist rebuilt the material: leave it alone
    amt = nodes["Foam Amount"]
    amt.inputs[1].default_value = s.foam_amount
    baked = s.mode == "BAKED"
    _unlink_input(nt, amt.inputs[0])
    if s.foam:
        if baked and nodes["Foam Sequence"].image is not None:
            links.new(nodes["Foam Sequence"].outputs["Color"], amt.inputs[0])
        elif not baked:
            links.new(nodes["Foam Attribute"].outputs["Fac"], amt.inputs[0])
        else:
            amt.inputs[0].default_value = 0.0
    else:
        amt.inputs[0].default_value = 0.0
    vt = nodes["Normal to World"]
    _unlink_input(nt, vt.inputs["Vector"])
    for bsdf in (nodes["Water"], nodes["Foam BSDF"]):
        _unlink_input(nt, bsdf.inputs["Normal"])
    source = None
    if s.normals:
        if baked and nodes["Normal Sequence"].image is not None:
            source = nodes["Normal Sequence"].outputs["Color"]
        elif not baked:
            source = nodes["Normal Attribute"].outputs["Vector"]
    if source is not None:
        links.new(source, vt.inputs["Vector"])
        for bsdf in (nodes["Water"], nodes["Foam BSDF"]):
            links.new(vt.outputs["Vector"], bsdf.inputs["Normal"])
