"""Render a scene with Blender Cycles (CPU) as a reference / peer measurement.

Run inside Blender (tested with Debian bookworm's blender 3.4.1):

    blender -b --factory-startup --python tools/cycles_render.py -- [ARGS]

Everything after the lone "--" is parsed by this script.  Examples:

    # built-in Cornell box, 256x256, 16 spp, written as linear float EXR
    blender -b --factory-startup --python cycles_render.py -- \
        --cornell --spp 16 --width 256 --height 256 --out out/cb16.exr

    # write the built-in Cornell box as JSON (to replicate it elsewhere)
    blender -b --factory-startup --python cycles_render.py -- --cornell --dump-scene cb.json

    # render a scene described by numbers (see SCENE JSON below)
    blender -b --factory-startup --python cycles_render.py -- --scene cb.json --spp 64 --out x.exr

    # a PLY/OBJ mesh lit by a constant white environment
    blender -b --factory-startup --python cycles_render.py -- \
        --mesh bunny.ply --env 1,1,1 --albedo 0.5,0.5,0.5 --spp 64 --out bunny.exr

SCENE JSON (all coordinates are used as-is, no axis conversion; units arbitrary):

    {
      "camera": {"pos": [x,y,z], "gaze": [dx,dy,dz], "up": [ux,uy,uz],
                 "fovy_deg": 39.3, "width": 256, "height": 256},
      "materials": {
        "white": {"albedo": [0.73,0.73,0.73]},
        "light": {"albedo": [0,0,0], "emission": [17,12,4]}
      },
      "quads":     [{"v": [[..],[..],[..],[..]], "material": "white"}, ...],
      "triangles": [{"v": [[..],[..],[..]],      "material": "white"}, ...],
      "meshes":    [{"file": "a.ply", "material": "white",
                     "matrix": [16 numbers, row-major 4x4, optional]}],
      "environment": [r,g,b],            # constant radiance from every direction, optional
      "two_sided_emission": false        # optional, default false
    }

Conventions (what a matching renderer must do to converge to the same image):
  * Materials are Lambertian: albedo/pi BRDF (Diffuse BSDF with roughness 0).
  * "emission" is emitted radiance (Cycles Emission shader, strength 1 on a mesh).
    By default emission is one-sided: only from the side the geometric normal
    points to.  Quad (a,b,c,d) has normal cross(b-a, c-a) and is split into
    triangles (a,b,c) and (a,c,d).  Shading normals are the geometric ones
    (flat shading) unless --smooth is given.
  * --max-bounces N is Cycles' count: N = 0 is direct lighting only (emission
    seen by the camera plus one light-connection at the first hit); N = 1 adds
    one indirect diffuse bounce, and so on.  A path thus has at most N+1
    scattering vertices.
  * Russian roulette stays on (Cycles has no switch for it; --min-bounces
    delays it).  Clamping, light threshold, glossy blur, denoising and path
    guiding are all turned off; adaptive sampling too unless
    --adaptive-threshold T is given (Kiln's copy of this script: Kiln's
    `--adaptive T` follows the same rule, renderer/film/adaptive_sampling.h).
  * Pixel filter: Gaussian of width 0.01 px by default, the smallest Cycles
    allows, i.e. every camera ray goes (almost) through the pixel centre; a
    matching renderer samples pixel centres only (pbrt: box filter of radius
    0.005 or --disable-pixel-jitter).  Cycles 3.4's "box" filter ignores the
    width setting entirely (measured: widths 0.01, 1 and 3 give identical
    images, blurred over more than one pixel), so --filter box is no
    pixel-area box; Gaussian/Blackman-Harris honour --filter-width.
  * The EXR is scene-linear Rec.709 float32 RGB, no view transform.

The script prints machine-readable lines starting with "CYCLES_" (render wall
time per repeat, samples/s) and optionally writes them to --stats-json.
"""

import argparse
import json
import math
import os
import statistics
import sys
import time

import bpy
from mathutils import Matrix, Vector


# --------------------------------------------------------------------------
# built-in Cornell box (Cornell University's measured geometry, in mm)
# --------------------------------------------------------------------------

def cornell_scene(albedo=(0.725, 0.71, 0.68), red=(0.63, 0.065, 0.05),
                  green=(0.14, 0.45, 0.091), emission=(17.0, 12.0, 4.0),
                  blocks=True, light_y=548.7, light_scale=1.0,
                  width=256, height=256):
    """Return the Cornell box as a scene dict (same schema as --scene JSON)."""
    L = light_y
    cx, cz = 278.0, 279.5
    hx, hz = 65.0 * light_scale, 52.5 * light_scale
    # light quad, normal pointing down (-y)
    light = [[cx + hx, L, cz - hz], [cx + hx, L, cz + hz],
             [cx - hx, L, cz + hz], [cx - hx, L, cz - hz]]
    quads = [
        # floor (normal +y)
        {"v": [[552.8, 0, 0], [0, 0, 0], [0, 0, 559.2], [549.6, 0, 559.2]], "material": "white"},
        # ceiling (normal -y)
        {"v": [[556, 548.8, 0], [556, 548.8, 559.2], [0, 548.8, 559.2], [0, 548.8, 0]], "material": "white"},
        # back wall (normal -z)
        {"v": [[549.6, 0, 559.2], [0, 0, 559.2], [0, 548.8, 559.2], [556, 548.8, 559.2]], "material": "white"},
        # right wall as seen from the camera, x = 0 (normal +x)
        {"v": [[0, 0, 559.2], [0, 0, 0], [0, 548.8, 0], [0, 548.8, 559.2]], "material": "green"},
        # left wall as seen from the camera, x ~ 552 (normal ~ -x)
        {"v": [[552.8, 0, 0], [549.6, 0, 559.2], [556, 548.8, 559.2], [556, 548.8, 0]], "material": "red"},
        {"v": light, "material": "light"},
    ]
    if blocks:
        short_block = [
            [[130, 165, 65], [82, 165, 225], [240, 165, 272], [290, 165, 114]],
            [[290, 0, 114], [290, 165, 114], [240, 165, 272], [240, 0, 272]],
            [[130, 0, 65], [130, 165, 65], [290, 165, 114], [290, 0, 114]],
            [[82, 0, 225], [82, 165, 225], [130, 165, 65], [130, 0, 65]],
            [[240, 0, 272], [240, 165, 272], [82, 165, 225], [82, 0, 225]],
        ]
        tall_block = [
            [[423, 330, 247], [265, 330, 296], [314, 330, 456], [472, 330, 406]],
            [[423, 0, 247], [423, 330, 247], [472, 330, 406], [472, 0, 406]],
            [[472, 0, 406], [472, 330, 406], [314, 330, 456], [314, 0, 456]],
            [[314, 0, 456], [314, 330, 456], [265, 330, 296], [265, 0, 296]],
            [[265, 0, 296], [265, 330, 296], [423, 330, 247], [423, 0, 247]],
        ]
        for q in short_block + tall_block:
            quads.append({"v": [list(map(float, p)) for p in q], "material": "white"})
    return {
        "camera": {"pos": [278.0, 273.0, -800.0], "gaze": [0.0, 0.0, 1.0],
                   "up": [0.0, 1.0, 0.0],
                   # 2*atan(12.5/35): 35 mm lens on a 25 mm film
                   "fovy_deg": math.degrees(2.0 * math.atan(12.5 / 35.0)),
                   "width": width, "height": height},
        "materials": {
            "white": {"albedo": list(albedo)},
            "red": {"albedo": list(red)},
            "green": {"albedo": list(green)},
            "light": {"albedo": [0.0, 0.0, 0.0], "emission": list(emission)},
        },
        "quads": quads,
        "triangles": [],
        "meshes": [],
        "environment": [0.0, 0.0, 0.0],
        "two_sided_emission": False,
    }


# --------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------

def vec3(text):
    parts = [float(x) for x in text.split(",")]
    if len(parts) == 1:
        parts = parts * 3
    if len(parts) != 3:
        raise argparse.ArgumentTypeError("expected r,g,b or x,y,z (or one number)")
    return parts


def parse_args(argv):
    p = argparse.ArgumentParser(prog="cycles_render.py",
                                description="Cycles CPU peer renderer (see module docstring)")
    src = p.add_argument_group("scene source (combine freely)")
    src.add_argument("--cornell", action="store_true", help="built-in Cornell box")
    src.add_argument("--scene", help="scene JSON file (schema in the docstring)")
    src.add_argument("--mesh", action="append", default=[],
                     help="PLY or OBJ file to add (repeatable); coordinates used as-is")
    src.add_argument("--mesh-matrix", default=None,
                     help="16 comma-separated numbers, row-major 4x4, applied to every --mesh")
    cb = p.add_argument_group("built-in Cornell box parameters")
    cb.add_argument("--albedo", type=vec3, default=None,
                    help="albedo of the white surfaces (Cornell) or of --mesh objects")
    cb.add_argument("--grey-walls", action="store_true",
                    help="Cornell: left/right walls use --albedo instead of red/green")
    cb.add_argument("--no-blocks", action="store_true", help="Cornell: leave out the two blocks")
    cb.add_argument("--light-emission", type=vec3, default=None,
                    help="Cornell: light radiance (default 17,12,4)")
    cb.add_argument("--light-scale", type=float, default=1.0,
                    help="Cornell: scale of the 130x105 light quad about its centre")
    cam = p.add_argument_group("camera (overrides the scene's)")
    cam.add_argument("--camera-pos", type=vec3)
    cam.add_argument("--gaze", type=vec3)
    cam.add_argument("--up", type=vec3)
    cam.add_argument("--fovy", type=float, help="vertical field of view, degrees")
    cam.add_argument("--width", type=int)
    cam.add_argument("--height", type=int)
    ren = p.add_argument_group("rendering")
    ren.add_argument("--spp", type=int, default=16, help="samples per pixel")
    ren.add_argument("--max-bounces", type=int, default=8,
                     help="Cycles max bounces (0 = direct light only)")
    ren.add_argument("--min-bounces", type=int, default=0,
                     help="bounces before Russian roulette may start (Cycles min_light_bounces)")
    ren.add_argument("--threads", type=int, default=0, help="0 = all cores")
    ren.add_argument("--seed", type=int, default=0)
    ren.add_argument("--pattern", default="SOBOL", choices=["SOBOL", "PROGRESSIVE_MULTI_JITTER"])
    ren.add_argument("--filter", default="gaussian",
                     choices=["gaussian", "blackman-harris", "box"],
                     help="pixel filter (box ignores --filter-width in Cycles 3.4)")
    ren.add_argument("--filter-width", type=float, default=0.01,
                     help="filter width in pixels (min 0.01; default: pixel-centre sampling)")
    ren.add_argument("--light-sampling", default="MULTIPLE_IMPORTANCE_SAMPLING",
                     choices=["MULTIPLE_IMPORTANCE_SAMPLING", "FORWARD_PATH_TRACING",
                              "NEXT_EVENT_ESTIMATION"])
    ren.add_argument("--env", type=vec3, default=None,
                     help="constant environment radiance r,g,b (default: scene's, else black)")
    ren.add_argument("--two-sided-emission", action="store_true")
    ren.add_argument("--smooth", action="store_true", help="smooth-shade imported meshes")
    ren.add_argument("--adaptive-threshold", type=float, default=0.0,
                     help="adaptive sampling noise threshold (0 = off, this script's default); --spp is the maximum")
    ren.add_argument("--adaptive-min-samples", type=int, default=0,
                     help="adaptive sampling minimum samples (0 = Cycles' automatic max(4, ceil(16/t^0.3)))")
    ren.add_argument("--tile-size", type=int, default=0,
                     help="Cycles tile size (0 = Cycles default, whole image up to 2048)")
    out = p.add_argument_group("output")
    out.add_argument("--out", default=None, help="output .exr (float32, linear)")
    out.add_argument("--half", action="store_true", help="write half floats instead of float32")
    out.add_argument("--repeat", type=int, default=1,
                     help="render this many times in one process (timing); last one is written")
    out.add_argument("--stats-json", default=None, help="write timings here")
    out.add_argument("--dump-scene", default=None,
                     help="write the resolved scene as JSON (meshes by file name) and continue")
    out.add_argument("--dump-only", action="store_true", help="with --dump-scene: do not render")
    out.add_argument("--save-blend", default=None, help="also save the built .blend (debugging)")
    return p.parse_args(argv)


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
        for block in list(coll):
            coll.remove(block)


def make_material(name, spec, two_sided_emission):
    """Lambertian albedo plus optional (one-sided) emission."""
    albedo = spec.get("albedo", [0.0, 0.0, 0.0])
    emission = spec.get("emission", [0.0, 0.0, 0.0])
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "ALL"
    shaders = []
    if max(albedo) > 0.0 or max(emission) <= 0.0:
        diff = nt.nodes.new("ShaderNodeBsdfDiffuse")
        diff.inputs["Color"].default_value = (albedo[0], albedo[1], albedo[2], 1.0)
        diff.inputs["Roughness"].default_value = 0.0
        shaders.append(diff.outputs["BSDF"])
    if max(emission) > 0.0:
        em = nt.nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (emission[0], emission[1], emission[2], 1.0)
        em.inputs["Strength"].default_value = 1.0
        if not two_sided_emission:
            geo = nt.nodes.new("ShaderNodeNewGeometry")
            inv = nt.nodes.new("ShaderNodeMath")
            inv.operation = "SUBTRACT"
            inv.inputs[0].default_value = 1.0
            nt.links.new(geo.outputs["Backfacing"], inv.inputs[1])
            nt.links.new(inv.outputs["Value"], em.inputs["Strength"])
        shaders.append(em.outputs["Emission"])
    if len(shaders) == 1:
        nt.links.new(shaders[0], out.inputs["Surface"])
    else:
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(shaders[0], add.inputs[0])
        nt.links.new(shaders[1], add.inputs[1])
        nt.links.new(add.outputs["Shader"], out.inputs["Surface"])
    return mat


def add_polygons(name, tris, material):
    """tris: list of 3-vertex lists. One object, one material, flat shaded."""
    verts, faces = [], []
    for t in tris:
        base = len(verts)
        verts.extend(tuple(map(float, p)) for p in t)
        faces.append((base, base + 1, base + 2))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.validate()
    mesh.update()
    for poly in mesh.polygons:
        poly.use_smooth = False
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def import_mesh(path, material, matrix, smooth):
    before = set(bpy.data.objects)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".ply":
        bpy.ops.import_mesh.ply(filepath=path)
    elif ext == ".obj":
        # identity axis mapping: file coordinates are used unchanged
        bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z")
    else:
        raise SystemExit("unsupported mesh format: " + path)
    new = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    if not new:
        raise SystemExit("nothing imported from " + path)
    for obj in new:
        if bpy.context.scene.collection.objects.get(obj.name) is None and not obj.users_collection:
            bpy.context.scene.collection.objects.link(obj)
        obj.data.materials.clear()
        obj.data.materials.append(material)
        for poly in obj.data.polygons:
            poly.material_index = 0
            poly.use_smooth = bool(smooth)
        if not smooth and obj.data.has_custom_normals:
            bpy.context.view_layer.objects.active = obj
            with bpy.context.temp_override(object=obj, active_object=obj):
                bpy.ops.mesh.customdata_custom_splitnormals_clear()
        if matrix is not None:
            obj.matrix_world = matrix @ obj.matrix_world
    return new


def set_camera(cam_spec):
    pos = Vector(cam_spec["pos"])
    gaze = Vector(cam_spec["gaze"]).normalized()
    up = Vector(cam_spec["up"])
    z = -gaze                           # Blender cameras look down local -Z
    x = up.cross(z)
    if x.length < 1e-12:
        raise SystemExit("camera up is parallel to gaze")
    x.normalize()
    y = z.cross(x)
    m = Matrix(((x[0], y[0], z[0], pos[0]),
                (x[1], y[1], z[1], pos[1]),
                (x[2], y[2], z[2], pos[2]),
                (0.0, 0.0, 0.0, 1.0)))
    cam_data = bpy.data.cameras.new("cam")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(cam_spec["fovy_deg"])
    cam_data.clip_start = 1e-4 * max(1.0, pos.length)
    cam_data.clip_end = 1e12
    cam_data.shift_x = cam_data.shift_y = 0.0
    cam_obj = bpy.data.objects.new("cam", cam_data)
    bpy.context.scene.collection.objects.link(cam_obj)
    cam_obj.matrix_world = m
    bpy.context.scene.camera = cam_obj
    return cam_obj


def auto_camera(objs, width, height, fovy=40.0):
    """Frame the bounding box of objs, looking down -Z with +Y up."""
    lo = Vector((1e30, 1e30, 1e30))
    hi = Vector((-1e30, -1e30, -1e30))
    for obj in objs:
        for corner in obj.bound_box:
            w = obj.matrix_world @ Vector(corner)
            lo = Vector(map(min, lo, w))
            hi = Vector(map(max, hi, w))
    c = (lo + hi) * 0.5
    r = max((hi - lo).length * 0.5, 1e-6)
    d = r / math.tan(math.radians(fovy) * 0.5) * 1.05
    return {"pos": [c[0], c[1], c[2] + d], "gaze": [0.0, 0.0, -1.0], "up": [0.0, 1.0, 0.0],
            "fovy_deg": fovy, "width": width, "height": height}


def set_world(env):
    world = bpy.data.worlds.get("World") or bpy.data.worlds.new("World")
    bpy.context.scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    if bg is None:
        bg = world.node_tree.nodes.new("ShaderNodeBackground")
        out = world.node_tree.nodes.get("World Output") or \
            world.node_tree.nodes.new("ShaderNodeOutputWorld")
        world.node_tree.links.new(bg.outputs["Background"], out.inputs["Surface"])
    if env is None or max(env) <= 0.0:
        bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        bg.inputs["Strength"].default_value = 0.0
        world.cycles.sampling_method = "NONE"
    else:
        bg.inputs["Color"].default_value = (env[0], env[1], env[2], 1.0)
        bg.inputs["Strength"].default_value = 1.0
        # a constant background gains nothing from importance sampling
        world.cycles.sampling_method = "MANUAL"
        world.cycles.sample_map_resolution = 64


def configure_cycles(args, width, height):
    scene = bpy.context.scene
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x = width
    r.resolution_y = height
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.film_transparent = False
    r.use_border = False
    r.dither_intensity = 0.0
    r.use_persistent_data = False
    if args.threads > 0:
        r.threads_mode = "FIXED"
        r.threads = args.threads
    else:
        r.threads_mode = "AUTO"
    c = scene.cycles
    c.device = "CPU"
    c.feature_set = "SUPPORTED"
    c.samples = args.spp
    c.use_adaptive_sampling = args.adaptive_threshold > 0.0
    if c.use_adaptive_sampling:
        c.adaptive_threshold = args.adaptive_threshold
        c.adaptive_min_samples = args.adaptive_min_samples
    c.use_denoising = False
    c.use_preview_denoising = False
    c.sampling_pattern = args.pattern
    c.seed = args.seed
    c.use_animated_seed = False
    c.pixel_filter_type = args.filter.upper().replace("-", "_")
    c.filter_width = max(0.01, args.filter_width)
    c.max_bounces = args.max_bounces
    c.diffuse_bounces = args.max_bounces
    c.glossy_bounces = args.max_bounces
    c.transmission_bounces = args.max_bounces
    c.volume_bounces = 0
    c.transparent_max_bounces = args.max_bounces
    c.min_light_bounces = args.min_bounces
    c.min_transparent_bounces = 0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.blur_glossy = 0.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.direct_light_sampling_type = args.light_sampling
    if hasattr(c, "use_guiding"):
        c.use_guiding = False
    if args.tile_size > 0:
        c.use_auto_tile = True
        c.tile_size = args.tile_size
    for vl in scene.view_layers:
        vl.cycles.denoising_store_passes = False
        vl.use_pass_combined = True
        vl.use_pass_z = False
    # scene-linear output, no view transform / look / exposure
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.view_settings.use_curve_mapping = False
    scene.display_settings.display_device = "sRGB"
    scene.sequencer_colorspace_settings.name = "Linear"
    ims = r.image_settings
    ims.file_format = "OPEN_EXR"
    ims.color_mode = "RGB"
    ims.color_depth = "16" if args.half else "32"
    ims.exr_codec = "ZIP"
    ims.use_preview = False
    r.use_file_extension = False
    r.use_stamp = False


def build_scene(args):
    spec = None
    if args.scene:
        with open(args.scene) as f:
            spec = json.load(f)
    if args.cornell:
        white = args.albedo if args.albedo is not None else [0.725, 0.71, 0.68]
        cb = cornell_scene(
            albedo=white,
            red=white if args.grey_walls else (0.63, 0.065, 0.05),
            green=white if args.grey_walls else (0.14, 0.45, 0.091),
            emission=args.light_emission if args.light_emission is not None else (17.0, 12.0, 4.0),
            blocks=not args.no_blocks, light_scale=args.light_scale)
        if spec is None:
            spec = cb
        else:   # merge: the JSON file adds to / overrides the Cornell box
            cb["materials"].update(spec.get("materials", {}))
            cb["quads"] += spec.get("quads", [])
            cb["triangles"] += spec.get("triangles", [])
            cb["meshes"] += spec.get("meshes", [])
            if "camera" in spec:
                cb["camera"] = spec["camera"]
            for k in ("environment", "two_sided_emission"):
                if k in spec:
                    cb[k] = spec[k]
            spec = cb
    if spec is None:
        spec = {"materials": {}, "quads": [], "triangles": [], "meshes": []}
    spec.setdefault("materials", {})
    spec.setdefault("quads", [])
    spec.setdefault("triangles", [])
    spec.setdefault("meshes", [])
    if args.mesh:
        mesh_albedo = args.albedo if args.albedo is not None else [0.5, 0.5, 0.5]
        spec["materials"].setdefault("mesh", {"albedo": mesh_albedo})
        mm = None
        if args.mesh_matrix:
            mm = [float(x) for x in args.mesh_matrix.split(",")]
            if len(mm) != 16:
                raise SystemExit("--mesh-matrix needs 16 numbers")
        for path in args.mesh:
            entry = {"file": os.path.abspath(path), "material": "mesh"}
            if mm:
                entry["matrix"] = mm
            spec["meshes"].append(entry)
        if "environment" not in spec and args.env is None and \
                not any(max(m.get("emission", [0])) > 0 for m in spec["materials"].values()):
            spec["environment"] = [1.0, 1.0, 1.0]
            print("CYCLES_NOTE no light in scene: using a constant white environment")
    if args.env is not None:
        spec["environment"] = args.env
    if args.two_sided_emission:
        spec["two_sided_emission"] = True
    spec.setdefault("environment", [0.0, 0.0, 0.0])
    spec.setdefault("two_sided_emission", False)

    clear_scene()
    mats = {name: make_material(name, m, spec["two_sided_emission"])
            for name, m in spec["materials"].items()}
    by_mat = {}
    for q in spec["quads"]:
        a, b, c, d = q["v"]
        by_mat.setdefault(q["material"], []).extend([[a, b, c], [a, c, d]])
    for t in spec["triangles"]:
        by_mat.setdefault(t["material"], []).append(t["v"])
    objs = []
    for mname, tris in by_mat.items():
        if mname not in mats:
            raise SystemExit("unknown material: " + mname)
        objs.append(add_polygons("poly_" + mname, tris, mats[mname]))
    for m in spec["meshes"]:
        matrix = None
        if "matrix" in m:
            v = m["matrix"]
            matrix = Matrix((v[0:4], v[4:8], v[8:12], v[12:16]))
        objs.extend(import_mesh(m["file"], mats[m["material"]], matrix, args.smooth))
    if not objs:
        raise SystemExit("empty scene: give --cornell, --scene or --mesh")
    bpy.context.view_layer.update()

    cam = dict(spec.get("camera") or {})
    width = args.width or cam.get("width") or 256
    height = args.height or cam.get("height") or 256
    if "pos" not in cam:
        cam = auto_camera(objs, width, height, args.fovy or 40.0)
    for key, val in (("pos", args.camera_pos), ("gaze", args.gaze), ("up", args.up),
                     ("fovy_deg", args.fovy)):
        if val is not None:
            cam[key] = val
    cam["width"], cam["height"] = width, height
    spec["camera"] = cam
    set_camera(cam)
    set_world(spec["environment"])
    return spec, width, height


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = parse_args(argv)
    t0 = time.perf_counter()
    spec, width, height = build_scene(args)
    t_build = time.perf_counter() - t0
    if args.dump_scene:
        with open(args.dump_scene, "w") as f:
            json.dump(spec, f, indent=1)
        print("CYCLES_DUMPED", args.dump_scene)
        if args.dump_only:
            return
    configure_cycles(args, width, height)
    if args.save_blend:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save_blend))

    scene = bpy.context.scene
    out = os.path.abspath(args.out) if args.out else None
    times = []
    for i in range(max(1, args.repeat)):
        last = (i == max(1, args.repeat) - 1)
        if out and last:
            scene.render.filepath = out
        t = time.perf_counter()
        bpy.ops.render.render(write_still=bool(out and last))
        dt = time.perf_counter() - t
        times.append(dt)
        print("CYCLES_RENDER_WALL_S %d %.4f" % (i, dt), flush=True)
    med = statistics.median(times)
    threads = scene.render.threads
    px = width * height
    print("CYCLES_SUMMARY spp=%d res=%dx%d max_bounces=%d threads=%d filter=%s:%.2f "
          "build_s=%.3f render_wall_s_median=%.4f Msamples_per_s=%.4f" %
          (args.spp, width, height, args.max_bounces, threads, args.filter,
           scene.cycles.filter_width,
           t_build, med, px * args.spp / med / 1e6), flush=True)
    if out:
        print("CYCLES_WROTE", out)
    if args.stats_json:
        with open(args.stats_json, "w") as f:
            json.dump({"spp": args.spp, "width": width, "height": height,
                       "max_bounces": args.max_bounces, "threads": threads,
                       "filter": args.filter, "filter_width": scene.cycles.filter_width,
                       "render_wall_s": times, "render_wall_s_median": med,
                       "scene_build_s": t_build, "blender": bpy.app.version_string,
                       "out": out}, f, indent=1)


if __name__ == "__main__":
    try:
        main()
    except SystemExit as e:
        if e.code not in (None, 0):
            print("CYCLES_ERROR", e.code, file=sys.stderr)
            sys.stdout.flush()
            os._exit(2)
        raise
