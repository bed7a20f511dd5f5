"""The notebook's 3-D view: Scene.glb and World.animation give the .glb `ontogen run`
writes, byte for byte; World, Scene and Animation show themselves as a page that inlines
the bundled viewer and that .glb (tests/python/display_page_test.mjs draws them in
Chromium)."""

import base64
import html
import json
import os
import re

import pytest

import ontogen
import ontogen.display
from conftest import MODELS, cli

BRANCHING = MODELS / "branching.cell"


def viewer():
    script = ontogen.display.viewer_script()
    if script is None:
        if os.environ.get("CI") == "true":
            pytest.fail("the module was built without viewer.js (esbuild and three.js: bash .ci/setup)")
        pytest.skip("the module was built without viewer.js")
    return script


def page_of(view):
    """The page an iframe's srcdoc holds."""
    match = re.fullmatch(r'<iframe srcdoc="([^"]*)" style="[^"]*" title="[^"]*"></iframe>', view)
    assert match, view[:200]
    return html.unescape(match.group(1))


def glb_of(page):
    return base64.b64decode(re.search(r'id="ontogen-model">([A-Za-z0-9+/=]*)</script>', page).group(1))


def times_of(page):
    return json.loads(re.search(r'id="ontogen-times">([^<]*)</script>', page).group(1))


def test_scene_glb_is_the_glb_run_writes(tmp_path):
    program = ontogen.load(BRANCHING)
    world = program.world(seed=program.seed)
    world.advance(program.until)
    cli("run", BRANCHING, "--out", tmp_path, "--format", "glb", "--frames", "1")
    assert world.scene().glb() == (tmp_path / "branching.glb").read_bytes()


def test_animation_is_the_glb_run_writes(tmp_path):
    program = ontogen.load(BRANCHING)
    world = program.world(seed=program.seed)
    animation = world.animation(4, 9)
    assert world.time == 4
    assert animation.times == [0.5 * i for i in range(9)]
    cli("run", BRANCHING, "--out", tmp_path, "--format", "glb", "--frames", "9", "--until", "4")
    assert animation.glb == (tmp_path / "branching.glb").read_bytes()
    animation.save(tmp_path / "saved.glb")
    assert (tmp_path / "saved.glb").read_bytes() == animation.glb


def test_an_animation_goes_on_from_the_worlds_time():
    program = ontogen.load(BRANCHING)
    world = program.world()
    world.advance(2)
    animation = world.animation(4, 3)
    assert animation.times == [2.0, 3.0, 4.0]
    assert world.animation(5, 1).times == [5.0]  # one frame: the end
    with pytest.raises(ValueError, match="at least one frame"):
        world.animation(6, 0)
    with pytest.raises(ValueError, match="finite"):
        world.animation(float("inf"), 2)
    with pytest.raises(ValueError, match="no set 'nothing'"):
        world.animation(6, 2, sets=("nothing",))


def test_world_scene_and_animation_show_the_viewer_and_their_glb():
    script = viewer()
    world = ontogen.load(BRANCHING).world()
    world.advance(3)
    scene = world.scene()
    for view, glb, times in ((world._repr_html_(), scene.glb(), [3.0]),
                             (scene._repr_html_(), scene.glb(), [3.0])):
        page = page_of(view)
        assert f"<script>{script}</script>" in page
        assert glb_of(page) == glb and glb[:4] == b"glTF"
        assert times_of(page) == times
    animation = world.animation(4, 3)
    page = page_of(animation._repr_html_())
    assert f"<script>{script}</script>" in page
    assert glb_of(page) == animation.glb
    assert times_of(page) == [3.0, 3.5, 4.0]


def test_a_world_shows_its_programs_drawing_sets():
    viewer()
    program = ontogen.compile("#interpret music\n#interpret geometry\nlsystem a {\n  axiom F\n  F -> F F\n}\n")
    world = program.world()
    world.advance(2)
    assert glb_of(page_of(world._repr_html_())) == world.scene(sets=("geometry",)).glb()
