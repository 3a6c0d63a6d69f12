// imapsim: IMAP-VISION stereo co-simulation tool. With no subcommand it runs
// the main job: `imapsim run` on the built-in synthetic scene.
#include <cstdio>
#include <iostream>
#include <vector>

#include "cli_common.hpp"
#include "imap/engine/error.hpp"
#include "imap/golden/params.hpp"
#include "imap/vision/image_io.hpp"

namespace {

// Runs the selected subcommand (run without one) and maps its errors to
// messages and exit codes.
int dispatch(std::vector<imapsim::Subcommand>& subs) {
    using namespace imapsim;
    try {
        for (auto& s : subs)
            if (s.app->parsed()) return s.run();
        return subs.front().run();  // no subcommand: the main job
    } catch (const imap::engine::Error& e) {
        std::cerr << "imapsim: error: " << e.what() << "\n";
        return e.code();
    } catch (const imap::vision::InputError& e) {
        std::cerr << "imapsim: error: " << e.what() << "\n";
        return kExitInput;
    } catch (const imap::golden::ParamError& e) {
        std::cerr << "imapsim: error: " << e.what() << "\n";
        return kExitInput;
    } catch (const std::exception& e) {
        std::cerr << "imapsim: internal error: " << e.what() << "\n";
        return kExitInternal;
    }
}

}  // namespace

int main(int argc, char** argv) {
    using namespace imapsim;
    CLI::App app{"imapsim - IMAP-VISION stereo co-simulation (golden reference, models, tools)"};
    app.require_subcommand(0, 1);
    app.set_version_flag("--version", "imapsim 0.1.0");
    app.footer(
        "With no command, imapsim runs 'imapsim run': the DP firmware on the TLM model of the "
        "array with the built-in synthetic scene, checked bit for bit against the golden "
        "('imapsim run --help' lists its flags).\n\n"
        "Exit codes: 0 success; 1 the model's output differs from the golden; 2 bad flags or "
        "input (nothing written); 3 the modeled machine faulted; 4 internal error; 5 a stream "
        "or sweep finished but some frames or points failed (listed in its log); 130 "
        "interrupted (partial results written). Messages: docs/errors.md.");
    std::vector<Subcommand> subs = {register_run(app), register_golden(app), register_eval(app),
                                    register_synth(app), register_bench(app)};
#ifdef IMAPSIM_HAVE_ISA
    subs.push_back(register_asm(app));
    subs.push_back(register_disasm(app));
    subs.push_back(register_exec(app));
#endif
#ifdef IMAPSIM_HAVE_REGRESS
    subs.push_back(register_regress(app));
#endif
#ifdef IMAPSIM_HAVE_STREAM
    subs.push_back(register_stream(app));
#endif
#ifdef IMAPSIM_HAVE_RTL
    subs.push_back(register_rtl_cache(app));
#endif
    subs.push_back(register_sweep(app));
    subs.push_back(register_table1(app));
    subs.push_back(register_run_task(app));
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        const std::string unknown = explain_unknown_arguments(app, argc, argv);
        std::cerr << "imapsim: error: " << (unknown.empty() ? e.what() : unknown)
                  << (unknown.empty() ? " (see --help)\n" : "\n");
        return kExitInput;
    }
    return dispatch(subs);
}
