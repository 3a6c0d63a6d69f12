// "Did you mean" for misspelt subcommands and options: a parse error of
// CLI11 that names extra arguments is re-explained from the command line.
#include <algorithm>
#include <string>
#include <vector>

#include "cli_common.hpp"

namespace imapsim {

namespace {

// Edit distance with adjacent transpositions (optimal string alignment).
size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

// The closest of `names` to `word`, if it is close enough to be a typo
// (at most a third of the word's letters, at least one, differ).
std::string closest(const std::string& word, const std::vector<std::string>& names) {
    std::string best;
    size_t best_d = std::max<size_t>(1, word.size() / 3) + 1;
    for (const std::string& n : names) {
        const size_t d = edit_distance(word, n);
        if (d < best_d) best_d = d, best = n;
    }
    return best;
}

std::vector<std::string> long_names(const CLI::App* app) {
    std::vector<std::string> out;
    for (const CLI::Option* o : app->get_options())
        for (const std::string& n : o->get_lnames()) out.push_back("--" + n);
    return out;
}

}  // namespace

std::string explain_unknown_arguments(CLI::App& app, int argc, char** argv) {
    std::vector<std::string> commands;
    for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; }))
        commands.push_back(s->get_name());
    const CLI::App* sub = nullptr;
    int first = 1;
    if (argc > 1 && argv[1][0] != '-') {
        const std::string cmd = argv[1];
        for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; }))
            if (s->get_name() == cmd) sub = s;
        if (sub == nullptr) {
            const std::string near = closest(cmd, commands);
            return "unknown command '" + cmd + "'" +
                   (near.empty() ? std::string() : " (did you mean " + near + "?)") +
                   "; commands: " + [&] {
                       std::string all;
                       for (const std::string& c : commands)
                           if (c != "run-task") all += (all.empty() ? "" : ", ") + c;
                       return all;
                   }();
        }
        first = 2;
    } else {
        // no subcommand: the flags are run's
        for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; }))
            if (s->get_name() == "run") sub = s;
    }
    if (sub == nullptr) return "";
    std::vector<std::string> names = long_names(sub);
    for (const std::string& n : long_names(&app)) names.push_back(n);
    for (int i = first; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--") break;
        if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) continue;
        const std::string name = arg.substr(0, arg.find('='));
        if (std::find(names.begin(), names.end(), name) != names.end()) continue;
        const std::string near = closest(name, names);
        return "unknown option " + name + (near.empty() ? "" : " (did you mean " + near + "?)") +
               " for imapsim " + sub->get_name() + "; imapsim " + sub->get_name() +
               " --help lists its options";
    }
    return "";
}

}  // namespace imapsim
