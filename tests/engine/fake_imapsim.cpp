// A stand-in for `imapsim run` in the executor tests: behaves as told by its
// flags, fast and independent of the firmware.
//   fake_imapsim run --model M [--exit N] [--sleep S] [--cycles C] [--mismatch]
//                    [--no-report] [--kill] [--message TEXT] [--marker FILE] --report R
// --marker FILE: appends "start" and "end" lines (concurrency checks).
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

int main(int argc, char** argv) {
    std::string report, model = "fake", message = "something is wrong", marker;
    int code = 0;
    double sleep_s = 0;
    unsigned long long cycles = 1000;
    bool mismatch = false, no_report = false, kill_self = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
        if (a == "--report")
            report = next();
        else if (a == "--model")
            model = next();
        else if (a == "--exit")
            code = std::atoi(next().c_str());
        else if (a == "--sleep")
            sleep_s = std::atof(next().c_str());
        else if (a == "--cycles")
            cycles = std::strtoull(next().c_str(), nullptr, 10);
        else if (a == "--message")
            message = next();
        else if (a == "--marker")
            marker = next();
        else if (a == "--mismatch")
            mismatch = true;
        else if (a == "--no-report")
            no_report = true;
        else if (a == "--kill")
            kill_self = true;
    }
    if (!marker.empty()) std::ofstream(marker, std::ios::app) << "start\n";
    std::printf("fake %s running\n", model.c_str());
    std::fflush(stdout);
    if (sleep_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(sleep_s));
    if (!marker.empty()) std::ofstream(marker, std::ios::app) << "end\n";
    if (kill_self) ::raise(SIGKILL);
    if (mismatch && code == 0) code = 1;
    if ((code == 0 || code == 1) && !no_report && !report.empty()) {
        std::ofstream r(report);
        r << "{\"model\": \"" << model << "\", \"bit_exact\": " << (mismatch ? "false" : "true")
          << ", \"differing_pixels\": " << (mismatch ? 3 : 0);
        if (mismatch)
            r << ", \"first_difference\": {\"x\": 4, \"y\": 5, \"model\": 7, \"golden\": 6}";
        r << ", \"cycles\": " << cycles << ", \"modeled_ms\": " << cycles / 40000.0
          << ", \"phases\": {\"forward\": " << cycles * 3 / 4
          << ", \"relayout_in\": " << cycles - cycles * 3 / 4 << "}, \"pe_utilisation\": 0.5}\n";
    }
    if (code != 0 && code != 1) std::fprintf(stderr, "imapsim: error: %s\n", message.c_str());
    return code;
}
