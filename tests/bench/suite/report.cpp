// The report: CSV of every point, gnuplot scripts and PNGs of the work-precision diagrams
// (when gnuplot is installed), and Markdown tables in DIR/summary.md for docs/benchmarks.md.
#include "bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>

namespace tumble::bench {

namespace {

std::ofstream openOut(const Options& opt, const std::string& name, bool append = false) {
    std::filesystem::create_directories(opt.out);
    return std::ofstream(opt.out / name, append ? std::ios::app : std::ios::trunc);
}

std::string num(double x, const char* fmt = "%.3g") {
    if (std::isinf(x)) return "inf";
    if (std::isnan(x)) return "nan";
    char b[64];
    std::snprintf(b, sizeof b, fmt, x);
    return b;
}

double perSimSecond(const AccuracyRow& r) {
    return 1e3 * r.wall / (r.steps * r.dt);  // ms of wall time per simulated second
}

bool haveGnuplot() {
    return std::system("command -v gnuplot >/dev/null 2>&1") == 0;
}

}  // namespace

void writeAccuracy(const Options& opt, const std::vector<AccuracyRow>& rows) {
    if (rows.empty()) return;
    std::ofstream csv = openOut(opt, "accuracy.csv");
    csv << "scene,engine,mode,dt,steps,wall_s,ms_per_step,error_name,error\n";
    for (const AccuracyRow& r : rows)
        csv << r.scene << ',' << r.engine << ',' << r.mode << ',' << num(r.dt, "%.10g") << ',' << r.steps
            << ',' << num(r.wall, "%.6g") << ',' << num(1e3 * r.wall / r.steps, "%.6g") << ',' << r.errorName
            << ',' << num(r.error, "%.6g") << '\n';

    // The main error of each scene is its first; plots for every error name.
    std::vector<std::pair<std::string, std::string>> plots;  // scene, error name
    std::map<std::string, std::string> mainError;
    for (const AccuracyRow& r : rows) {
        if (!mainError.count(r.scene)) mainError[r.scene] = r.errorName;
        if (std::find(plots.begin(), plots.end(), std::pair(r.scene, r.errorName)) == plots.end())
            plots.emplace_back(r.scene, r.errorName);
    }
    std::filesystem::create_directories(opt.out / "data");
    const bool gnuplot = haveGnuplot();
    for (const auto& [scene, errorName] : plots) {
        std::vector<std::string> series;
        for (const AccuracyRow& r : rows) {
            if (r.scene != scene || r.errorName != errorName) continue;
            const std::string key = r.engine + " " + r.mode;
            const std::string file =
                "data/" + scene + "." + errorName + "." + r.engine + "." + r.mode + ".dat";
            const bool first = std::find(series.begin(), series.end(), key) == series.end();
            if (first) series.push_back(key);
            std::ofstream dat = openOut(opt, file, !first);
            if (std::isfinite(r.error))
                dat << num(perSimSecond(r), "%.6g") << ' ' << num(std::max(r.error, 1e-16), "%.6g") << ' '
                    << num(1 / r.dt, "%.0f") << '\n';
        }
        const std::string base = "bench-" + scene + (errorName == mainError[scene] ? "" : "-" + errorName);
        std::ofstream gp = openOut(opt, base + ".gp");
        gp << "# work-precision diagram, written by tumble-bench; run in " << opt.out.string() << "\n"
           << "set terminal pngcairo size 800,560 noenhanced font 'DejaVu Sans,10'\n"
           << "set output '" << base << ".png'\n"
           << "set title '" << scene << ": " << errorName << " against run time'\n"
           << "set logscale xy\nset format y '%.0e'\nset grid\nset key outside right\n"
           << "set xlabel 'wall time per simulated second (ms), steps 1/30 ... 1/3840 s'\n"
           << "set ylabel '" << errorName << " (floor 1e-16)'\nplot ";
        for (size_t i = 0; i < series.size(); ++i) {
            const size_t sp = series[i].find(' ');
            const std::string file = "data/" + scene + "." + errorName + "." + series[i].substr(0, sp) + "." +
                                     series[i].substr(sp + 1) + ".dat";
            // Tumble solid and thick; each peer its own dash, so engines read apart in print.
            const std::string engine = series[i].substr(0, sp);
            const int dash = engine == "tumble" ? 1 : engine == "bullet" ? 2 : engine == "ode" ? 3 : engine == "mujoco" ? 4 : 5;
            gp << (i ? ", \\\n     " : "") << "'" << file << "' using 1:2 with linespoints dashtype " << dash
               << " linewidth " << (dash == 1 ? 2 : 1) << " title '" << series[i] << "'";
        }
        gp << "\n";
        gp.close();
        if (gnuplot) {
            const std::string cmd = "cd '" + opt.out.string() + "' && gnuplot '" + base + ".gp' 2>&1";
            if (std::system(cmd.c_str()) != 0) std::printf("gnuplot failed on %s.gp\n", base.c_str());
        }
    }
    if (!gnuplot) std::printf("gnuplot not found: the plot scripts are in %s (*.gp)\n", opt.out.c_str());

    // Markdown: the main error and the time per simulated second of each point; then
    // Tumble's cheapest run at each error level against the cheapest peer's.
    std::ofstream md = openOut(opt, "summary.md", true);
    for (const auto& [scene, errorName] : mainError) {
        std::vector<double> dts;
        for (const AccuracyRow& r : rows)
            if (r.scene == scene && std::find(dts.begin(), dts.end(), r.dt) == dts.end()) dts.push_back(r.dt);
        md << "\n#### " << scene << ": " << errorName << " (ms per simulated second)\n\n| engine | mode |";
        for (double dt : dts) md << " 1/" << num(1 / dt, "%.0f") << " |";
        md << "\n|---|---|";
        for (size_t i = 0; i < dts.size(); ++i) md << "--:|";
        md << "\n";
        std::vector<std::string> keys;
        for (const AccuracyRow& r : rows)
            if (r.scene == scene && r.errorName == errorName &&
                std::find(keys.begin(), keys.end(), r.engine + "|" + r.mode) == keys.end())
                keys.push_back(r.engine + "|" + r.mode);
        for (const std::string& k : keys) {
            md << "| " << k.substr(0, k.find('|')) << " | " << k.substr(k.find('|') + 1) << " |";
            for (double dt : dts) {
                std::string cell = " ";
                for (const AccuracyRow& r : rows)
                    if (r.scene == scene && r.errorName == errorName && r.engine + "|" + r.mode == k &&
                        r.dt == dt)
                        // A run that stopped (its guard or a non-finite state threw) has no time.
                        cell = r.wall < 1e299 ? num(r.error, "%.2g") + " (" + num(perSimSecond(r), "%.2g") + ")"
                                              : std::string("stopped");
                md << ' ' << cell << " |";
            }
            md << '\n';
        }
        // Error levels: every decade between the best and the worst finite error.
        double lo = 1e300, hi = 0;
        for (const AccuracyRow& r : rows)
            if (r.scene == scene && r.errorName == errorName && std::isfinite(r.error) && r.error > 0)
                lo = std::min(lo, r.error), hi = std::max(hi, r.error);
        if (hi == 0) continue;
        md << "\n| " << errorName
           << " <= | tumble: cheapest run (ms/sim-s) | fastest peer | tumble / peer |\n"
           << "|---|---|---|---|\n";
        std::vector<std::pair<std::string, std::string>> lines;  // cells, the row
        for (int k = static_cast<int>(std::ceil(std::log10(hi)));
             k >= static_cast<int>(std::ceil(std::log10(lo))); --k) {
            const double target = std::pow(10.0, k);
            const AccuracyRow* best[2] = {nullptr, nullptr};  // tumble, peer
            for (const AccuracyRow& r : rows) {
                if (r.scene != scene || r.errorName != errorName || !(r.error <= target)) continue;
                const AccuracyRow*& b = best[r.engine == "tumble" ? 0 : 1];
                if (!b || perSimSecond(r) < perSimSecond(*b)) b = &r;
            }
            auto cell = [](const AccuracyRow* r) {
                return r ? num(perSimSecond(*r), "%.3g") + " (" + r->engine + " " + r->mode + ", 1/" +
                               num(1 / r->dt, "%.0f") + ")"
                         : std::string("not reached");
            };
            // Of the levels with the same two runs only the strictest is shown: the table shows
            // where the cost steps.
            const std::string cells = cell(best[0]) + " | " + cell(best[1]);
            if (!lines.empty() && lines.back().first == cells) lines.pop_back();
            lines.emplace_back(
                cells, "| 1e" + std::to_string(k) + " | " + cells + " | " +
                           (best[0] && best[1] ? num(perSimSecond(*best[0]) / perSimSecond(*best[1]), "%.2f")
                                               : "-") +
                           " |\n");
        }
        for (const auto& line : lines) md << line.second;
    }
}

namespace {

// Tumble's step by stage, as a share of the fastest peer's step in the same run, one stacked
// bar per scene (the headline mode, end-of-step, one thread): the issue-17 target is a bar
// at or below the line at 1.
void plotStages(const Options& opt, const std::vector<SpeedRow>& rows) {
    const std::string headline = "splitting+end-of-step";
    std::filesystem::create_directories(opt.out / "data");
    std::ofstream dat = openOut(opt, "data/speed-stages.dat");
    dat << "# scene integrate broadphase narrowphase time-of-impact impact-solve contact-solve rest peer\n";
    int bars = 0;
    for (const SpeedRow& t : rows) {
        if (t.engine != "tumble" || t.mode != headline || !t.note.empty() || !(t.msPerStep > 0)) continue;
        const SpeedRow* peer = nullptr;
        for (const SpeedRow& r : rows)
            if (r.scene == t.scene && r.engine != "tumble" && r.note.empty() && r.msPerStep > 0 &&
                (!peer || r.msPerStep < peer->msPerStep))
                peer = &r;
        if (!peer) continue;
        const double k = 1.0 / peer->msPerStep;
        const double stages = t.forces + t.integrate + t.broadphase + t.narrowphase + t.toi + t.impact +
                              t.solve + t.sleep;
        dat << t.scene << ' ' << num((t.forces + t.integrate) * k, "%.4g") << ' ' << num(t.broadphase * k, "%.4g")
            << ' ' << num(t.narrowphase * k, "%.4g") << ' ' << num(t.toi * k, "%.4g") << ' '
            << num(t.impact * k, "%.4g") << ' ' << num(t.solve * k, "%.4g") << ' '
            << num(std::max(0.0, t.msPerStep - stages) * k + t.sleep * k, "%.4g") << " \"" << peer->engine
            << "\"\n";
        ++bars;
    }
    dat.close();
    if (bars == 0) return;
    std::ofstream gp = openOut(opt, "bench-speed-stages.gp");
    gp << "# Tumble's step by stage over the fastest peer's step, written by tumble-bench; run in "
       << opt.out.string() << "\n"
       << "set terminal pngcairo size 900,520 noenhanced font 'DejaVu Sans,10'\n"
       << "set output 'bench-speed-stages.png'\n"
       << "set title 'Tumble (" << headline << ", one thread): step time by stage / fastest peer step time'\n"
       << "set style data histograms\nset style histogram rowstacked\nset style fill solid 0.8 border -1\n"
       << "set boxwidth 0.7\nset key outside right\nset grid y\nset yrange [0:*]\n"
       << "set xtics rotate by -30\nset ylabel 'share of the fastest peer step (1 = level)'\n"
       << "plot 'data/speed-stages.dat' using 2:xtic(1) title 'integrate', \\\n"
       << "     '' using 3 title 'broadphase', '' using 4 title 'narrowphase', \\\n"
       << "     '' using 5 title 'time of impact', '' using 6 title 'impact solve', \\\n"
       << "     '' using 7 title 'contact solve', '' using 8 title 'sleep and the rest', \\\n"
       << "     1 with lines linewidth 2 linecolor rgb 'black' title 'fastest peer'\n";
    gp.close();
    if (haveGnuplot()) {
        const std::string cmd = "cd '" + opt.out.string() + "' && gnuplot bench-speed-stages.gp 2>&1";
        if (std::system(cmd.c_str()) != 0) std::printf("gnuplot failed on bench-speed-stages.gp\n");
    }
}

}  // namespace

void writeSpeed(const Options& opt, const std::vector<SpeedRow>& rows) {
    if (rows.empty()) return;
    std::ofstream csv = openOut(opt, "speed.csv");
    csv << "scene,engine,mode,bodies,steps,ms_per_step,ms_max_step,contacts_per_step,peak_mb,base_mb,forces_"
           "ms,"
           "integrate_ms,broadphase_ms,narrowphase_ms,toi_ms,impact_ms,solve_ms,sleep_ms,pairs_per_step,"
           "awake_per_step,cuts_per_step,parked_per_step,restarts_per_step,moving_at_end,fell_through,joint_gap_m,note\n";
    for (const SpeedRow& r : rows)
        csv << r.scene << ',' << r.engine << ',' << r.mode << ',' << r.bodies << ',' << r.steps << ','
            << r.msPerStep << ',' << r.msMaxStep << ',' << r.contactsPerStep << ',' << r.peakMB << ','
            << r.baseMB << ',' << r.forces << ',' << r.integrate << ',' << r.broadphase << ','
            << r.narrowphase << ',' << r.toi << ',' << r.impact << ',' << r.solve << ',' << r.sleep << ','
            << r.pairsPerStep << ',' << r.awakePerStep << ',' << r.cutsPerStep << ','
           << r.parkedPerStep << ',' << r.restartsPerStep << ',' << r.movingAtEnd << ',' << r.fellThrough
           << ',' << (r.jointGap >= 0.0 ? num(r.jointGap, "%.6g") : std::string()) << ",\"" << r.note << "\"\n";
    std::ofstream md = openOut(opt, "summary.md", true);
    md << "\n| scene | engine | mode | bodies | steps | ms/step | slowest step | contacts/step | memory (MB) "
          "| moving at the end | fell through | largest joint gap (mm) |\n"
       << "|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const SpeedRow& r : rows) {
        if (!r.note.empty()) {
            md << "| " << r.scene << " | " << r.engine << " | " << r.mode << " | " << r.note
               << " | | | | | | | | |\n";
            continue;
        }
        md << "| " << r.scene << " | " << r.engine << " | " << r.mode << " | " << r.bodies << " | " << r.steps
           << " | " << num(r.msPerStep) << " | " << num(r.msMaxStep) << " | "
           << num(r.contactsPerStep, "%.0f") << " | " << num(r.peakMB - r.baseMB, "%.1f") << " | "
           << r.movingAtEnd << " | " << r.fellThrough << " | "
           << (r.jointGap >= 0.0 ? num(1e3 * r.jointGap, "%.3g") : std::string()) << " |\n";
    }
    md << "\nTumble per stage (ms per step):\n\n| scene | mode | forces | integrate | broadphase | narrowphase | "
          "time of impact "
          "| impact solve | contact solve | sleep | pairs/step | awake bodies/step | cuts/step | parked/step | "
          "restarts/step |\n"
       << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const SpeedRow& r : rows)
        if (r.engine == "tumble" && r.note.empty())
            md << "| " << r.scene << " | " << r.mode << " | " << num(r.forces) << " | " << num(r.integrate) << " | "
               << num(r.broadphase) << " | " << num(r.narrowphase) << " | " << num(r.toi) << " | "
               << num(r.impact) << " | " << num(r.solve) << " | " << num(r.sleep) << " | "
               << num(r.pairsPerStep, "%.0f") << " | " << num(r.awakePerStep, "%.0f") << " | "
               << num(r.cutsPerStep, "%.2f") << " | " << num(r.parkedPerStep, "%.0f") << " | "
               << num(r.restartsPerStep, "%.3f") << " |\n";
    plotStages(opt, rows);
}

namespace {

// The stacks at the steps people use: each stack's largest move against the step, a line per
// engine, one panel per stack (the tests named "STACK@1/N"); a run that broke or fell over
// is drawn at 10 m.
void plotStability(const Options& opt, const std::vector<StressRow>& rows) {
    std::vector<std::string> stacks, engines;
    for (const StressRow& r : rows) {
        const size_t at = r.test.find("@1/");
        if (at == std::string::npos || !(r.dt > 0)) continue;
        const std::string stack = r.test.substr(0, at);
        if (std::find(stacks.begin(), stacks.end(), stack) == stacks.end()) stacks.push_back(stack);
        if (std::find(engines.begin(), engines.end(), r.engine) == engines.end()) engines.push_back(r.engine);
    }
    if (stacks.empty()) return;
    std::filesystem::create_directories(opt.out / "data");
    for (const std::string& stack : stacks)
        for (const std::string& engine : engines) {
            std::vector<std::pair<double, double>> points;  // steps per second, largest move
            for (const StressRow& r : rows)
                if (r.engine == engine && r.dt > 0 && r.test.rfind(stack + "@1/", 0) == 0)
                    points.emplace_back(1.0 / r.dt, std::clamp(r.largestMove, 1e-16, 10.0));
            std::sort(points.begin(), points.end());
            std::ofstream dat = openOut(opt, "data/stability." + stack + "." + engine + ".dat");
            for (const auto& [rate, move] : points) dat << num(rate, "%.0f") << ' ' << num(move, "%.4g") << '\n';
        }
    const int columns = stacks.size() > 2 ? 3 : static_cast<int>(stacks.size());
    const int lines = (static_cast<int>(stacks.size()) + columns - 1) / columns;
    std::ofstream gp = openOut(opt, "bench-stability.gp");
    gp << "# the stacks' largest move against the step, written by tumble-bench; run in " << opt.out.string()
       << "\nset terminal pngcairo size " << 380 * columns << "," << 320 * lines
       << " noenhanced font 'DejaVu Sans,9'\nset output 'bench-stability.png'\n"
       << "set multiplot layout " << lines << "," << columns
       << " title 'largest drift or sink of a box (m) against steps per second, sleeping off'\n"
       << "set logscale xy\nset format y '%.0e'\nset grid\nset xrange [20:400]\nset yrange [1e-16:20]\n"
       << "set xtics (30, 60, 240)\nset key bottom right\n";
    for (const std::string& stack : stacks) {
        gp << "set title '" << stack << "'\nplot ";
        for (size_t i = 0; i < engines.size(); ++i) {
            const int dash = engines[i] == "tumble" ? 1 : engines[i] == "bullet" ? 2 : engines[i] == "ode" ? 3 : engines[i] == "mujoco" ? 4 : 5;
            gp << (i ? ", " : "") << "'data/stability." << stack << "." << engines[i]
               << ".dat' using 1:2 with linespoints dashtype " << dash << " linewidth " << (dash == 1 ? 2 : 1)
               << " title '" << engines[i] << "'";
        }
        gp << ", 0.01 with lines linecolor rgb 'gray' title '1 cm'\n";
    }
    gp << "unset multiplot\n";
    gp.close();
    if (haveGnuplot()) {
        const std::string cmd = "cd '" + opt.out.string() + "' && gnuplot bench-stability.gp 2>&1";
        if (std::system(cmd.c_str()) != 0) std::printf("gnuplot failed on bench-stability.gp\n");
    }
}

}  // namespace

void writeStress(const Options& opt, const std::vector<StressRow>& rows) {
    if (rows.empty()) return;
    std::ofstream csv = openOut(opt, "stress.csv");
    csv << "test,engine,result,figure\n";
    for (const StressRow& r : rows)
        csv << r.test << ',' << r.engine << ',' << (r.pass ? "PASS" : "FAIL") << ",\"" << r.figure << "\"\n";
    std::ofstream md = openOut(opt, "summary.md", true);
    md << "\n| test | engine | result | figure |\n|---|---|---|---|\n";
    for (const StressRow& r : rows) {
        std::string figure;  // a | would end the table cell
        for (char c : r.figure) figure += c == '|' ? std::string("\\|") : std::string(1, c);
        md << "| " << r.test << " | " << r.engine << " | " << (r.pass ? "PASS" : "**FAIL**") << " | "
           << figure << " |\n";
    }
    plotStability(opt, rows);
}

}  // namespace tumble::bench
