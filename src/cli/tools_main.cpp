// tessera-tools: the image-analysis sub-commands of tessera (tools_exec.hpp):
// check, contact-sheet and bench. `tessera check ...` runs `tessera-tools
// check ...`, so usage and messages read as tessera's.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/bench_command.hpp"
#include "cli/check_command.hpp"
#include "cli/cli_docs.hpp"
#include "cli/contact_sheet_command.hpp"
#include "cli/frame_options.hpp"
#include "io/memory_budget.hpp"
#include "scene/gltf/gltf_import.hpp"
#include "cli/usage.hpp"

int main(int argc, char** argv) {
    CLI::App app{"Tessera: a multithreaded SIMD CPU rasterizer with a PBR fragment stage", "tessera"};
    app.set_version_flag("--version", "tessera " TESSERA_VERSION);
    app.require_subcommand(1);
    app.option_defaults()->always_capture_default();  // every --help shows the defaults

    tessera::cli::BenchCommand bench;
    CLI::App* bench_app = app.add_subcommand("bench", "Render a scene many times and report time per stage");
    bench_app->add_option("scene", bench.scene_path, "Scene file: a .toml scene, or a .gltf/.glb model on its own")
        ->required();
    bench_app->add_option("--frames", bench.frames, "Frames to time")->check(CLI::Range(1, 100000));
    bench_app->add_option("--warmup", bench.warmup, "Frames rendered before timing")->check(CLI::Range(0, 100000));
    tessera::cli::add_frame_options(bench_app, bench.width, bench.height, bench.msaa, bench.settings);
    tessera::cli::add_lighting_options(bench_app, bench.lighting);
    bench_app->add_flag("--json", bench.json, "Print one JSON object");
    bench_app->add_flag("--cull-back-faces", bench.cull_back_faces,
                        "Draw every material single-sided (back faces culled), as double_sided = false");
    bench_app->add_flag("--radiance", bench.keep_radiance, "Also keep the HDR radiance image, as a render to EXR does");
    bench_app->add_option("--trace", bench.trace_path,
                          "Write the timed frames as a Chrome trace-event JSON file (Perfetto, chrome://tracing): "
                          "a track per worker, a span per pass, chunk and tile");
    bench_app->add_option("--heatmap", bench.heatmap_path,
                          "Write a PNG of the frame with each tile tinted by its cost");
    bench_app->add_option("--heatmap-metric", bench.heatmap_metric,
                          "What the heat map shows: time (ms per tile, median of the timed frames) or work "
                          "(fragments x lights per tile)")
        ->check(CLI::IsMember({"time", "work"}));

    tessera::cli::CheckCommand check;
    CLI::App* check_app = tessera::cli::add_check_command(app, check);

    tessera::cli::ContactSheetCommand contact_sheet;
    CLI::App* contact_sheet_app = tessera::cli::add_contact_sheet_command(app, contact_sheet);

    // Hostile input (docs/robustness.md), as for render.
    std::string max_memory;
    bool allow_external_uris = false;
    for (CLI::App* command : {bench_app, check_app, contact_sheet_app}) {
        command->add_option("--max-memory", max_memory,
                            "Memory budget for what one input may decode to, e.g. 4G or 512M; default: half of "
                            "physical memory, or TESSERA_MAX_MEMORY");
        if (command != contact_sheet_app)
            command->add_flag("--allow-external-uris", allow_external_uris,
                              "Let glTF URIs name files outside the model's folder (refused by default)");
    }

    tessera::cli::hide_empty_defaults(app);
    // For tessera --print-completion / --print-man (cli_docs.hpp): these commands' definitions.
    if (argc == 2 && argv[1] == tessera::cli::kSpecRequest) {
        std::fputs(tessera::cli::to_spec(tessera::cli::describe_commands(app)).c_str(), stdout);
        return 0;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return tessera::cli::report_parse_error(app, e, argc, argv);
    }
    try {
        if (!max_memory.empty()) tessera::io::set_memory_budget(tessera::io::parse_byte_size(max_memory));
        tessera::set_external_uris_allowed(allow_external_uris);
        if (*bench_app) return tessera::cli::run_bench(bench);
        if (*contact_sheet_app) return tessera::cli::run_contact_sheet(contact_sheet);
        if (*check_app) return tessera::cli::run_check(check);
    } catch (const tessera::cli::UsageError& e) {
        tessera::cli::print_error(e.what());
        return tessera::cli::kUsageExit;
    } catch (const std::exception& e) {
        tessera::cli::print_error(tessera::io::error_sentence(e));
        return 1;
    }
    return 1;
}
