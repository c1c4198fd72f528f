#!/usr/bin/env python3
"""Write a scene JSON (the schema of tools/cycles_render.py) as a CENG795 XML scene that
Kiln path-traces to the image cycles_render.py converges to.  Stdlib only.

Usage:
    python3 tools/scene_to_ceng795.py SCENE.json OUT.xml [--max-bounces N] [--spp N]
        [--mode course|kiln] [--image NAME.exr]

    # example: the Cornell box, Cycles' default 8 bounces
    blender -b --factory-startup --python tools/cycles_render.py -- \
        --cornell --dump-scene cb.json --dump-only
    python3 tools/scene_to_ceng795.py cb.json cb.xml --max-bounces 8 --spp 4096
    kiln render cb.xml -o out --strategy mis --threads 2 --seed 1
    # (the tool prints the Kiln command lines that match, for every strategy)

Mapping (checked against Kiln's code: scenes/material_mapping.cpp, materials/blinn_phong.cpp,
lights/mesh_light.h, renderer/integrators/integrator.cpp, renderer/integrators/path_tracer.cpp, renderer/render/render.cpp):
  * Material: albedo a -> <Material BRDF="1"> with DiffuseReflectance a, Specular and Ambient 0,
    BRDF 1 = <ModifiedBlinnPhong normalized="true"> (Exponent 1).  Kiln evaluates it as
    kd/pi + ks (p+8)/(8 pi) cos^p = a/pi exactly when ks = 0, and samples it with pure cosine
    sampling (glossy lobe probability 0).  The CENG795 XML has no Lambert element; a material
    without BRDF would be the course's *un-normalised* classic shading (kd, not kd/pi).
  * Emitters: material with "emission" -> <LightMesh> with Radiance = emission (radiance,
    one-sided: Kiln emits toward (v1-v0)x(v2-v0), the JSON's cross(b-a, c-a)).  Its Material is
    left out when albedo is 0 (black back side, as Cycles' emission-only shader), else it gets
    the Lambertian material too.  two_sided_emission is refused (Kiln's mesh lights are
    one-sided only).
  * Quads (a,b,c,d) -> triangles (a,b,c), (a,c,d); flat shading.  "meshes": PLY only
    (<Faces plyFile=absolute path>), "matrix" -> a Composite transformation (row-major 4x4,
    the same layout).  OBJ is refused.  A non-black "environment" is refused (Kiln parses
    environment lights but does not render them; BackgroundColor reaches camera rays only).
  * Camera: type="lookAt" with Position = pos, Gaze = gaze, Up = up, FovY = fovy_deg (full
    vertical angle), NearDistance 1, ImageResolution W H.  CENG795's frame w = -gaze,
    u = up x w is the one cycles_render.py builds, so images are not mirrored.
  * Depth.  Cycles' --max-bounces N means at most N+1 scattering vertices.  Kiln has two
    depth semantics (renderer/integrators/path_tracer.cpp, integrator.cpp):
      - Kiln's own (scene without <Renderer>, strategy from --strategy): depth D = D
        scattering vertices, the vertex at depth D only collects emission: D = N + 1 for
        every strategy.
      - course semantics (<Renderer>PathTracing</Renderer>): NEE also runs at the vertex at
        depth D ("nee_at_last_vertex", kept by --strategy overrides), so NEE and MIS paths
        have D+1 scattering vertices (D = N) while brdf/cosine/uniform have D (D = N + 1).
    --mode course (default) writes <Renderer>PathTracing</Renderer>, RendererParams
    "NextEventEstimation ImportanceSampling" and MaxRecursionDepth N: `kiln render OUT.xml`
    alone then path-traces the right image (course NEE+IS, no roulette); `--strategy mis`
    or `nee` keep D = N; brdf/cosine/uniform need `--max-depth N+1`.
    --mode kiln writes no <Renderer> and MaxRecursionDepth N+1: every `--strategy`
    (required: without it Kiln runs the course's direct-lighting ray tracer) matches Cycles,
    with Kiln's own roulette (after 3 bounces) on.
  * Russian roulette: Cycles always uses it (unbiased).  Course mode has none unless
    `--rr true` is given (same expected image either way; use --rr true for timing).
  * Pixel sampling: Cycles samples pixel centres (Gaussian 0.01 px).  Kiln's default is the
    1-px box (stratified jitter over the pixel; pixel centre only at spp = 1); give it
    `--filter gaussian:0.01` to sample centres as Cycles does (race.py does), or the same
    `--filter blackman-harris:W` as Cycles' --filter blackman-harris --filter-width W; the
    images then agree pixel by pixel, not only per block.
  * Output: Kiln writes OUT_DIR/<ImageName stem>.exr (linear float32 RGB, plus a PNG).
"""
import argparse
import json
import math
import os
import sys


def fmt(xs):
    return " ".join("%.9g" % float(x) for x in xs)


def main():
    ap = argparse.ArgumentParser(description="scene JSON -> CENG795 XML for Kiln (see docstring)")
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--max-bounces", type=int, default=8, help="Cycles' count (default 8)")
    ap.add_argument("--spp", type=int, default=16, help="NumSamples written (kiln --spp overrides)")
    ap.add_argument("--mode", choices=["course", "kiln"], default="course",
                    help="depth semantics (see docstring); default course")
    ap.add_argument("--image", default=None, help="ImageName (default: OUT's stem + .exr)")
    a = ap.parse_args()
    if a.max_bounces < 0:
        raise SystemExit("--max-bounces must be >= 0")
    spec = json.load(open(a.scene))
    if spec.get("two_sided_emission", False):
        raise SystemExit("two_sided_emission: Kiln's LightMesh emits from its front side only")
    env = spec.get("environment", [0, 0, 0]) or [0, 0, 0]
    if max(env) > 0:
        raise SystemExit("environment %s: Kiln does not render environment light" % env)
    cam = spec["camera"]
    image = a.image or os.path.splitext(os.path.basename(a.out))[0] + ".exr"
    depth = a.max_bounces if a.mode == "course" else a.max_bounces + 1
    mats = spec["materials"]
    used = []
    for q in spec.get("quads", []) + spec.get("triangles", []) + spec.get("meshes", []):
        if q["material"] not in mats:
            raise SystemExit("unknown material: " + q["material"])
        if q["material"] not in used:
            used.append(q["material"])
    mat_id = {}
    for name in used:
        if max(mats[name].get("albedo", [0, 0, 0])) > 0 or max(mats[name].get("emission", [0, 0, 0])) <= 0:
            mat_id[name] = len(mat_id) + 1

    o = ["<!-- generated by scene_to_ceng795.py from %s: --max-bounces %d (Cycles' count), mode %s -->"
         % (os.path.basename(a.scene), a.max_bounces, a.mode), "<Scene>"]
    o.append("    <MaxRecursionDepth>%d</MaxRecursionDepth>" % depth)
    o.append("    <BackgroundColor>0 0 0</BackgroundColor>")
    o.append("    <Cameras>")
    o.append('        <Camera id="1" type="lookAt">')
    o.append("            <Position>%s</Position>" % fmt(cam["pos"]))
    o.append("            <Gaze>%s</Gaze>" % fmt(cam["gaze"]))
    o.append("            <Up>%s</Up>" % fmt(cam["up"]))
    o.append("            <FovY>%.9g</FovY>" % cam["fovy_deg"])
    o.append("            <NearDistance>1</NearDistance>")
    o.append("            <ImageResolution>%d %d</ImageResolution>" % (cam["width"], cam["height"]))
    o.append("            <NumSamples>%d</NumSamples>" % a.spp)
    o.append("            <ImageName>%s</ImageName>" % image)
    if a.mode == "course":
        o.append("            <Renderer>PathTracing</Renderer>")
        o.append("            <RendererParams>NextEventEstimation ImportanceSampling</RendererParams>")
    o.append("        </Camera>")
    o.append("    </Cameras>")
    o.append("    <BRDFs>")
    o.append('        <ModifiedBlinnPhong id="1" normalized="true"> <!-- ks = 0: exactly kd/pi -->')
    o.append("            <Exponent>1</Exponent>")
    o.append("        </ModifiedBlinnPhong>")
    o.append("    </BRDFs>")
    o.append("    <Materials>")
    for name, mid in mat_id.items():
        o.append('        <Material id="%d" BRDF="1"> <!-- %s -->' % (mid, name))
        o.append("            <AmbientReflectance>0 0 0</AmbientReflectance>")
        o.append("            <DiffuseReflectance>%s</DiffuseReflectance>" % fmt(mats[name].get("albedo", [0, 0, 0])))
        o.append("            <SpecularReflectance>0 0 0</SpecularReflectance>")
        o.append("        </Material>")
    o.append("    </Materials>")

    # geometry: one vertex list, one (Light)Mesh per material
    groups = {}
    for q in spec.get("quads", []):
        v = q["v"]
        groups.setdefault(q["material"], []).extend([[v[0], v[1], v[2]], [v[0], v[2], v[3]]])
    for t in spec.get("triangles", []):
        groups.setdefault(t["material"], []).append(t["v"])
    verts, faces = [], {}
    for name, tris in groups.items():
        idx = []
        for t in tris:
            for p in t:
                verts.append(p)
                idx.append(len(verts))  # 1-based
        faces[name] = idx
    xforms = []
    for m in spec.get("meshes", []):
        if "matrix" in m:
            if len(m["matrix"]) != 16:
                raise SystemExit("mesh matrix needs 16 numbers")
            xforms.append(m["matrix"])
    if xforms:
        o.append("    <Transformations>")
        for i, mx in enumerate(xforms):
            o.append('        <Composite id="%d">%s</Composite>' % (i + 1, fmt(mx)))
        o.append("    </Transformations>")
    o.append("    <VertexData>")
    for p in verts:
        o.append("        %s" % fmt(p))
    o.append("    </VertexData>")
    o.append("    <Objects>")
    n_mesh = n_light = 0

    def obj(name, faces_xml, xform=None):
        nonlocal n_mesh, n_light
        em = mats[name].get("emission", [0, 0, 0])
        if max(em) > 0:
            n_light += 1
            o.append('        <LightMesh id="%d"> <!-- %s -->' % (n_light, name))
            if name in mat_id:
                o.append("            <Material>%d</Material>" % mat_id[name])
            o.append("            <Radiance>%s</Radiance>" % fmt(em))
            tag = "LightMesh"
        else:
            n_mesh += 1
            o.append('        <Mesh id="%d" shadingMode="flat"> <!-- %s -->' % (n_mesh, name))
            o.append("            <Material>%d</Material>" % mat_id[name])
            tag = "Mesh"
        if xform:
            o.append("            <Transformations>%s</Transformations>" % xform)
        o.append(faces_xml)
        o.append("        </%s>" % tag)

    for name, idx in faces.items():
        lines = ["            <Faces>"]
        for k in range(0, len(idx), 3):
            lines.append("                %d %d %d" % tuple(idx[k:k + 3]))
        lines.append("            </Faces>")
        obj(name, "\n".join(lines))
    xi = 0
    for m in spec.get("meshes", []):
        path = os.path.abspath(m["file"])
        if not path.lower().endswith(".ply"):
            raise SystemExit("Kiln's XML reads PLY meshes only: " + m["file"])
        xf = None
        if "matrix" in m:
            xi += 1
            xf = "c%d" % xi
        obj(m["material"], '            <Faces plyFile="%s"/>' % path, xf)
    o.append("    </Objects>")
    o.append("</Scene>")
    with open(a.out, "w") as f:
        f.write("\n".join(o) + "\n")
    n = a.max_bounces
    print("wrote %s (mode %s, MaxRecursionDepth %d for Cycles --max-bounces %d)" % (a.out, a.mode, depth, n))
    if a.mode == "course":
        print("kiln render %s -o DIR --spp S --strategy mis   # also nee; or no --strategy (course NEE+IS)" % a.out)
        print("kiln render %s -o DIR --spp S --strategy cosine --max-depth %d   # brdf/uniform too" % (a.out, n + 1))
    else:
        print("kiln render %s -o DIR --spp S --strategy mis|nee|brdf|cosine|uniform" % a.out)


if __name__ == "__main__":
    main()
