"""Seed scenes for the fuzzer that hold what the renderer's emitter and BSDF models read: area emitters on every
shape it traces (an OBJ mesh, a rectangle, a disk, a sphere, a cylinder), spot, directional, point and constant
emitters, twosided BSDFs nested and referred to by id, and the `direct` integrator with its parameters.
"""
from __future__ import annotations

#: Area emitters on each kind of shape over a two-sided floor, under `direct` with all its parameters.
AREA_SCENE = b"""<scene version="3.0.0">
    <default name="res" value="32"/>
    <integrator type="direct">
        <integer name="emitter_samples" value="2"/>
        <integer name="bsdf_samples" value="1"/>
        <boolean name="hide_emitters" value="false"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 3, 6" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/>
            <rfilter type="box"/></film>
    </sensor>
    <bsdf type="twosided" id="grey"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></bsdf>
    <shape type="rectangle"><transform name="to_world"><scale value="5"/><rotate x="1" angle="-90"/></transform>
        <ref id="grey"/></shape>
    <shape type="rectangle">
        <transform name="to_world"><scale x="0.5" y="0.3" z="1"/><rotate x="1" angle="90"/><translate y="2.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="6, 5, 4"/></emitter></shape>
    <shape type="disk">
        <transform name="to_world"><scale value="0.4"/><rotate x="1" angle="60"/><translate x="-1.5" y="1.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>
    <shape type="sphere"><point name="center" value="1.5, 1, 0"/><float name="radius" value="0.3"/>
        <emitter type="area"><rgb name="radiance" value="2, 3, 4"/></emitter></shape>
    <shape type="cylinder"><point name="p0" value="-1, 0.2, -1"/><point name="p1" value="-0.5, 1.2, -1.2"/>
        <float name="radius" value="0.2"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.2, 0.2"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
    <shape type="obj"><string name="filename" value="mesh.obj"/>
        <transform name="to_world"><scale value="0.8"/><translate x="0.2" z="0.5"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.7, 0.3"/></bsdf>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.9"/></bsdf></bsdf>
        <emitter type="area"><rgb name="radiance" value="0.5"/></emitter></shape>
</scene>
"""
#: The delta lights and the environment, over shapes whose twosided BSDFs nest and refer to one another.
DELTA_SCENE = b"""<scene version="3.0.0">
    <default name="res" value="32"/>
    <integrator type="direct"><integer name="shading_samples" value="2"/>
        <boolean name="hide_emitters" value="true"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="3, 2.5, 4" target="0, 0.3, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
    </sensor>
    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.7, 0.1, 0.1"/></bsdf>
    <bsdf type="twosided" id="both"><ref id="red"/><bsdf type="diffuse"><rgb name="reflectance" value="0.3"/></bsdf></bsdf>
    <bsdf type="twosided" id="nested"><bsdf type="twosided"><ref id="both"/></bsdf></bsdf>
    <shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform>
        <ref id="nested"/></shape>
    <shape type="sphere"><point name="center" value="0, 0.5, 0"/><float name="radius" value="0.5"/><ref id="both"/></shape>
    <shape type="cube"><transform name="to_world"><scale value="0.3"/><translate x="1" y="0.3" z="-0.5"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>
    <emitter type="spot">
        <transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
        <rgb name="intensity" value="20"/>
        <float name="cutoff_angle" value="30"/>
        <float name="beam_width" value="20"/>
    </emitter>
    <emitter type="directional"><vector name="direction" value="-1, -2, -0.5"/><rgb name="irradiance" value="2"/></emitter>
    <emitter type="point"><point name="position" value="-2, 2, 2"/><rgb name="intensity" value="5"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>
</scene>
"""
#: (name, scene file) of each seed; their meshes are the fuzzer's tetrahedron (mesh.obj).
LIGHT_SEEDS = (("area_shapes", AREA_SCENE), ("delta_lights", DELTA_SCENE))
