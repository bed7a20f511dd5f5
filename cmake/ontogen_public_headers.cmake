# The installed API: the headers a program using the package includes, and the headers
# they include, no more (docs/EMBEDDING.md says what each is for). Every other header is
# private to its library and stays in the source tree. The `public_headers` test
# (tests/package/public_headers_test.cmake) fails if one of these includes a header not
# listed here, or if the list passes 60; the `package` test checks the install tree the
# same way and builds tests/package against it.
#
# The entry points: compile a program (lang/compiler.h, lang/source_reader.h,
# model/diagnostics.h), convert .l and .lpy files (lang/convert/convert.h), grow a world
# with limits and read it (core/world.h, core/word.h, core/limits.h, core/parents.h,
# interpreters/text/word_text.h), interpret it (interpreters/set_registry.h,
# interpreters/interpret.h, interpreters/scene.h), a run (interpreters/run.h) and a sweep
# (batch/sweep.h). The rest is what those include.
set(ONTOGEN_PUBLIC_HEADERS
  pools/cell_cursor.h
  pools/cell_record.h
  pools/cell_view.h
  pools/compact_word.h
  pools/grid_pool.h
  pools/id_replay.h
  pools/large_block_cache.h
  pools/large_page_allocator.h
  pools/linear_pool.h
  pools/mix_key.h
  pools/pool.h
  pools/spatial_pool.h
  pools/value_operation.h
  model/builtins.h
  model/diagnostics.h
  model/expression.h
  model/program.h
  model/random.h
  model/source.h
  lang/ast.h
  lang/compiler.h
  lang/convert/convert.h
  lang/convert/lsystem_file.h
  lang/source_reader.h
  lang/token.h
  lang/variation.h
  core/development.h
  core/environment_process.h
  core/limits.h
  core/module_value.h
  core/parents.h
  core/rewrite_plan.h
  core/salts.h
  core/successors.h
  core/word.h
  core/world.h
  interpreters/formats/look.h
  interpreters/formats/renderer.h
  interpreters/formats/scene_output.h
  interpreters/formats/svg_writer.h
  interpreters/formats/up_axis.h
  interpreters/geometry.h
  interpreters/interpret.h
  interpreters/interpretation_set.h
  interpreters/run.h
  interpreters/scene.h
  interpreters/set_registry.h
  interpreters/sweep/contact_sheet.h
  interpreters/sweep/measure.h
  interpreters/sweep/sweep_table.h
  interpreters/sweep/variant_run.h
  interpreters/text/word_text.h
  batch/batch_run.h
  batch/cluster.h
  batch/sweep.h
  batch/sweep_setup.h
)
