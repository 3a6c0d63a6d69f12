// Running a sweep (run): the plan's jobs on an executor (resumed from the
// run folder's results), each result applied to its row and the rows
// printed in point order as they finish, what an interrupt left unfinished,
// the phase names of all reports, and the knees along the x axis; and the
// statuses and exit code of the result.
#include <algorithm>
#include <string>
#include <vector>

#include "imap/engine/error.hpp"
#include "imap/engine/sweep.hpp"
#include "sweep_detail.hpp"

namespace imap::engine::sweep {

using namespace detail;

const char* status_name(Status s) {
    for (const auto& [k, n] : kStatusNames)
        if (k == s) return n;
    return "?";
}

size_t Result::count(Status s) const {
    return static_cast<size_t>(
        std::count_if(rows.begin(), rows.end(), [s](const Row& r) { return r.status == s; }));
}

int Result::exit_code(bool dry_run) const {
    if (interrupted) return kExitInterrupted;
    if (count(Status::Error)) return kExitItemErrors;
    if (dry_run ? count(Status::Planned) == 0 : ran() == 0) return kExitItemErrors;
    if (count(Status::Mismatch)) return kExitMismatch;
    return kExitOk;
}

// ---- running --------------------------------------------------------------------------

namespace {

void apply(Row& row, RunResult r) {
    switch (r.outcome) {
        case Outcome::Ok:
            row.status = Status::Ok;
            row.message.clear();
            break;
        case Outcome::Mismatch:
            row.status = Status::Mismatch;
            row.message = describe(r);
            break;
        case Outcome::Interrupted:
            row.status = Status::Interrupted;
            row.message = describe(r);
            break;
        default:
            row.status = Status::Error;
            row.message = describe(r);
    }
    row.run = std::move(r);
}

}  // namespace

Result run(const Plan& p, Executor& ex, RunDir& dir, Manifest& m, const ExecContext& ctx,
           Hooks& hooks, bool resume, size_t x_axis) {
    Result res;
    res.total = p.rows.size();
    std::vector<Row> rows = p.rows;
    std::vector<bool> done(rows.size(), false);
    std::vector<size_t> row_of(p.jobs.size(), 0);
    for (size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].job >= 0 && static_cast<size_t>(rows[i].job) < row_of.size())
            row_of[static_cast<size_t>(rows[i].job)] = i;
        else
            done[i] = true;
    }
    size_t printed = 0;
    auto flush = [&]() {
        while (printed < rows.size() && done[printed]) hooks.row(row_line(p, rows[printed++]));
    };
    flush();
    ExecHooks eh;
    eh.stop_requested = hooks.stop_requested;
    eh.on_note = hooks.note;
    eh.on_status = hooks.status;
    eh.on_result = [&](size_t j, RunResult r) {
        const size_t i = row_of[j];
        apply(rows[i], std::move(r));
        done[i] = true;
        flush();
    };
    DriveOutcome d;
    if (!p.jobs.empty()) {
        d = drive(dir, m, ex, ctx, eh, resume);
    }
    res.interrupted = d.interrupted;
    res.reused = d.reused;
    res.wall_s = d.wall_s;
    // What finished after an interrupt (points that never ran are left out).
    for (size_t i = printed; i < rows.size(); ++i)
        if (done[i]) hooks.row(row_line(p, rows[i]));
    for (size_t i = 0; i < rows.size(); ++i) {
        if (done[i])
            res.rows.push_back(std::move(rows[i]));
        else
            ++res.not_run;
    }
    if (res.not_run) res.interrupted = true;
    // Phase names: the program's order, then any other name a report gave.
    res.phase_names = p.phase_names;
    for (const Row& r : res.rows)
        if (r.run)
            for (const auto& [n, c] : r.run->phases)
                if (std::find(res.phase_names.begin(), res.phase_names.end(), n) ==
                    res.phase_names.end())
                    res.phase_names.push_back(n);
    if (x_axis < p.swept.size()) {
        res.x_axis = p.swept[x_axis].name;
        res.knees = find_knees(p, res.rows, x_axis);
    }
    return res;
}

}  // namespace imap::engine::sweep
