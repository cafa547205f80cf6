// The command line as a whole, through the binary: the exit-code table of apps/exit_code.h,
// unknown words named with a suggestion, --version everywhere, and the bash completion script.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <thread>

#include "tests/apps/cli_test_util.h"

namespace gs::test {
namespace {

namespace fs = std::filesystem;

// The subcommands as `grainshock --help` lists them.
std::vector<std::string> subcommands() {
  const std::string help = grainshock("--help").out;
  std::vector<std::string> names;
  const auto at = help.find("Subcommands:");
  EXPECT_NE(at, std::string::npos) << help;
  const std::regex line(R"(\n  ([a-z]+) )");
  for (std::sregex_iterator it(help.begin() + at, help.end(), line), end; it != end; ++it)
    names.push_back((*it)[1]);
  return names;
}

TEST(CliUsage, HelpListsEverySubcommandAndTheExitCodes) {
  const auto names = subcommands();
  for (const char* want :
       {"run", "render", "movie", "ensemble", "merge", "figures", "bench", "compare", "completion",
        "view"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  const auto r = grainshock("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* row :
       {"  0    success", "  1    user error", "  2    usage error", "  130  interrupted"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  EXPECT_NE(grainshock("run --help").out.find("Exit codes: 0 success, 1 user error"),
            std::string::npos);
}

TEST(CliUsage, VersionOnEverySubcommand) {
  const std::string top = grainshock("--version").out;
  EXPECT_TRUE(std::regex_match(top, std::regex(R"(\d+\.\d+\.\d+\n)"))) << top;
  for (const std::string& sub : subcommands()) {
    const auto r = grainshock(sub + " --version");
    EXPECT_EQ(r.exit_code, 0) << sub << ": " << r.err;
    EXPECT_EQ(r.out, top) << sub;
  }
}

TEST(CliUsage, UnknownWordsAreNamedWithTheNearestValidOne) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"rnu", "unknown subcommand 'rnu'; did you mean 'run'?"},
      {"rendr x.xyz", "unknown subcommand 'rendr'; did you mean 'render'?"},
      {"frobnicate", "unknown subcommand 'frobnicate'"},
      {"run --partcles 10", "unknown flag '--partcles' for 'run'; did you mean '--particles'?"},
      {"run --particles 10 --t-mx 5", "unknown flag '--t-mx' for 'run'; did you mean '--t-max'?"},
      {"movie --particels 10",
       "unknown flag '--particels' for 'movie'; did you mean '--particles'?"},
      {"--verison", "unknown flag '--verison'; did you mean '--version'?"},
      {"compare a.png b.png --tolerence=3",
       "unknown flag '--tolerence' for 'compare'; did you mean '--tolerance'?"},
      {"run --zzzzzz", "unknown flag '--zzzzzz' for 'run'"},
      {"", "a subcommand is required: run, resume, render,"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = grainshock(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("grainshock: error: " + message, 0), 0u) << args << ": " << r.err;
  }
  // A flag far from every valid one gets no guess.
  EXPECT_EQ(grainshock("run --zzzzzz").err.find("did you mean"), std::string::npos);
}

// Waits for `file` to appear (the child is past its set-up), then sends `sig`; the exit code.
int interrupt_when(pid_t pid, const fs::path& file, int sig) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(file) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(kill(pid, sig), 0);
  int status = 0;
  EXPECT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status)) << "killed by the signal instead of winding down";
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(CliUsage, ExitCodeTable) {
  const fs::path dir = scratch_dir("codes");
  fs::create_directories(dir / "full");
  std::ofstream(dir / "full" / "old.txt") << "earlier results\n";
  const std::string small = "--dim 2 --medium box --particles 200 --t-max 20 --quiet --out ";
  struct Case {
    std::string args;
    int code;
  };
  const std::vector<Case> cases = {
      {"--version", 0},
      {"run --help", 0},
      {"run " + small + (dir / "ok").string(), 0},
      {"completion bash", 0},
      // user errors: the command line is understood, but what it asks cannot be done
      {"run " + small + (dir / "full").string(), 1},
      {"run --density 0.9 --out " + (dir / "dense").string(), 1},
      {"render " + (dir / "missing.xyz").string() + " --out " + (dir / "m.png").string(), 1},
      {"merge " + (dir / "full").string() + " --out " + (dir / "merged").string(), 1},
      // usage errors: the command line itself
      {"", 2},
      {"rnu", 2},
      {"run --partcles 10", 2},
      {"run --particles ten", 2},
      {"run --initial warm", 2},
      {"run --per-decade 0", 2},
      {"run --particles", 2},
      {"compare", 2},
      {"completion fish", 2},
      {"ensemble --realisations", 2},
  };
  for (const Case& c : cases) {
    const auto r = grainshock(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << ": " << r.err;
    if (c.code != 0) {
      EXPECT_EQ(r.err_lines(), 1) << c.args << ": " << r.err;
    }
  }
  EXPECT_EQ(read_file(dir / "full" / "old.txt"), "earlier results\n");

  // Interrupted: 130 for SIGINT and SIGTERM alike, with the files written so far complete.
  for (int sig : {SIGINT, SIGTERM}) {
    const fs::path out = dir / ("stopped_" + std::to_string(sig));
    const pid_t pid = spawn_grainshock(
        "run --dim 3 --medium box --particles 20000 --t-max 1e7 --quiet --out " + out.string());
    EXPECT_EQ(interrupt_when(pid, out / "timeseries.csv", sig), 130) << "signal " << sig;
    EXPECT_NE(read_file(out / "summary.json").find("\"interrupted\": true"), std::string::npos)
        << read_file(out / "summary.json");
  }
}

// One rule for every subcommand: a value outside what its flag accepts exits 2 with one line
// naming the flag, whether CLI11 or the job checks it, so `run --dim 4` and `render --dim 4`
// end alike.
TEST(CliUsage, OutOfRangeValuesExitTwoInEverySubcommand) {
  const fs::path dir = scratch_dir("range");
  const std::string small = "--dim 2 --medium box --particles 200 --t-max 20 --quiet";
  const auto made = grainshock("run " + small + " --out " + (dir / "ok").string());
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string snap = (dir / "ok" / "snapshots" / "tsim_20.xyz").string();
  ASSERT_TRUE(fs::exists(snap));
  const std::string png = (dir / "a.png").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run --dim 4 --out " + (dir / "r1").string(), "--dim"},
      {"run --restitution 1.5 --out " + (dir / "r2").string(), "--restitution"},
      {"run " + small + " --png --width 0 --out " + (dir / "r3").string(), "0x1080"},
      {"run " + small + " --sample-every -1 --out " + (dir / "r4").string(), "--sample-every"},
      {"resume --checkpoint-every -1 " + (dir / "ok").string(), "--checkpoint-every"},
      {"ensemble --dim 4 --out " + (dir / "e1").string(), "--dim"},
      {"ensemble --realisations 0 --out " + (dir / "e2").string(), "--realisations"},
      {"ensemble --resamples 3 --out " + (dir / "e3").string(), "--resamples"},
      {"movie --dim 4 --out " + (dir / "m1").string(), "--dim"},
      {"movie --frames 0 --out " + (dir / "m2").string(), "--frames"},
      {"movie --camera round --out " + (dir / "m3").string(), "--camera"},
      {"movie " + snap + " --seed 3 --out " + (dir / "m4").string(), "--seed"},
      {"render --dim 4 " + snap + " --out " + png, "--dim"},
      {"render " + snap + " --width 0 --out " + png, "0x1080"},
      {"render " + snap + " --zoom -1 --out " + png, "--zoom"},
      {"render " + snap + " --out " + (dir / "a.jpg").string(), "a.jpg"},
      {"compare --max-blob -1 " + png + " " + png, "--max-blob"},
      {"compare --diff " + (dir / "d.gif").string() + " " + png + " " + png, "d.gif"},
      {"figures --format jpg --out " + (dir / "f1").string(), "--format"},
      {"figures --threads 0 --out " + (dir / "f2").string(), "--threads"},
      {"figures --checkpoint-every -1 --out " + (dir / "f3").string(), "--checkpoint-every"},
      {"ensemble --checkpoint-every -1 --out " + (dir / "e4").string(), "--checkpoint-every"},
      {"ensemble --checkpoint-every 30 --checkpoint-minutes 1 --out " + (dir / "e5").string(),
       "--checkpoint-"},
      {"bench --repeat 0", "--repeat"},
      {"merge --resamples 3 " + (dir / "ok").string() + " --out " + (dir / "g1").string(),
       "--resamples"},
      {"completion fish", "fish"},
  };
  for (const auto& [args, named] : cases) {
    const auto r = grainshock(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << args << ": " << r.err;
  }
  for (const char* out : {"r1", "r2", "r3", "r4", "e1", "e2", "e3", "e4", "e5", "m1", "m2", "m3",
                          "m4", "f1", "f2", "f3", "g1", "a.png", "a.jpg"})
    EXPECT_FALSE(fs::exists(dir / out)) << out;
}

// Values the jobs and the renderer check after CLI11 (words, ranges, flags that exclude or need
// each other) are usage errors too: exit 2 with one line naming the flag, nothing written. Each
// row was accepted (exit 0) or exited 1 before.
TEST(CliUsage, ValuesCheckedPastTheParserExitTwoNamingTheFlag) {
  const fs::path dir = scratch_dir("past_parser");
  const std::string small = "--dim 2 --medium box --particles 200 --t-max 20 --quiet";
  const auto made = grainshock("run " + small + " --out " + (dir / "ok").string());
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string snap = (dir / "ok" / "snapshots" / "tsim_20.xyz").string();
  const std::string movie = "movie " + small + " --out " + (dir / "m").string() + " ";
  const std::string render = "render " + snap + " --out " + (dir / "r.png").string() + " ";
  const std::string figures = "figures --out " + (dir / "f").string() + " ";
  const std::string run = "run " + small + " --out " + (dir / "run").string() + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {movie + "--fps 0", "--fps"},
      {movie + "--fps nan", "--fps"},
      {movie + "--crf 99", "--crf"},
      {movie + "--codec vp9", "--codec"},
      {movie + "--color-by temperature", "--color-by"},
      {movie + "--colormap jet", "--colormap"},
      {movie + "--background blue", "--background"},
      {movie + "--gl vulkan", "--gl"},
      {movie + "--range 5 1", "--range"},
      {render + "--colormap jet", "--colormap"},
      {render + "--background blue", "--background"},
      {render + "--gl vulkan", "--gl"},
      {render + "--range 5 1", "--range"},
      {render + "--percentiles 99 1", "--percentiles"},
      {render + "--msaa -5", "--msaa"},
      {render + "--msaa 100000", "--msaa"},
      {figures + "--quick --full", "--full"},
      {figures + "--tiny --full", "--tiny"},
      {run + "--snapshot-times 10 --trajectory foo.txt", "--trajectory"},
      {run + "--movie-inset", "--movie-inset"},
      {"resume " + (dir / "ok").string() + " --threads 0", "--threads"},
      {"ensemble --threads 100000 --realisations 1 --out " + (dir / "e").string(), "--threads"},
  };
  for (const auto& [args, named] : cases) {
    const auto r = grainshock(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << args << ": " << r.err;
  }
  for (const char* out : {"m", "r.png", "f", "run", "e"}) EXPECT_FALSE(fs::exists(dir / out)) << out;
}

// A number is refused as typed, not as CLI11's conversion turned it: "" was reported as 0, -1 and
// a 23-digit seed as 18446744073709551615, 1e400 as "inf: must be positive"; and a bound is said
// in a few digits (CLI11's own printed DBL_MAX in full, 300 of them).
TEST(CliUsage, NumbersAreRefusedAsTyped) {
  const fs::path dir = scratch_dir("typed");
  const std::string run = "run --dim 2 --medium box --t-max 20 --quiet --out " +
                          (dir / "r").string() + " ";
  struct Case {
    std::string args, says, not_says;
  };
  const std::vector<Case> cases = {
      {run + "--particles ''", "--particles: an empty value is not a number", ": 0"},
      {run + "--seed -1", "--seed: '-1' is negative", "18446744073709551615"},
      {run + "--seed 12345678901234567890123",
       "--seed: '12345678901234567890123' is out of range", "18446744073709551615"},
      {run + "--t-max 1e400", "--t-max: '1e400' is out of range", "inf"},
      {run + "--density 1e-400", "--density: '1e-400' is out of range", "--density 0"},
      {run + "--sample-every -1", "--sample-every: -1 is negative", "1797693"},
      {"resume --checkpoint-every -1 " + dir.string(), "--checkpoint-every: -1 is negative",
       "1797693"},
      {"render --dt -1 x.xyz --out " + (dir / "a.png").string(), "--dt: -1 is not positive",
       "1797693"},
  };
  for (const Case& c : cases) {
    const auto r = grainshock(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(r.err.find(c.not_says), std::string::npos) << c.args << ": " << r.err;
    EXPECT_LT(r.err.size(), 200u) << c.args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "r"));
  // What the conversion reads rightly still passes: a count in physicists' notation, a hex seed.
  const auto ok = grainshock(run + "--particles 2e2 --seed 0x10");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// A garbage snapshot's bytes are quoted escaped: an ESC from the file must not reach the terminal.
TEST(CliUsage, GarbageIsQuotedEscaped) {
  const fs::path dir = scratch_dir("garbage");
  fs::create_directories(dir);
  std::ofstream(dir / "bad.xyz", std::ios::binary) << "\x1b[31mred\x1b[0m\x07 \xff\n2\n";
  const auto r = grainshock("render " + (dir / "bad.xyz").string() + " --out " +
                            (dir / "bad.png").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\x07'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'\\x1B[31mred\\x1B[0m\\x07 \\xFF' is not a particle count"),
            std::string::npos)
      << r.err;
}

// Files that are not what a command needs are named for what they are: a directory or a pipe
// was "no such file", a text file named .png "a movie", a checkpoint that is a directory
// "truncated".
TEST(CliUsage, WrongKindsOfFilesAreNamedForWhatTheyAre) {
  const fs::path dir = scratch_dir("kinds");
  const auto made = grainshock("run --dim 2 --medium box --particles 200 --t-max 20 --quiet "
                               "--png --width 64 --height 48 --out " + (dir / "ok").string());
  ASSERT_EQ(made.exit_code, 0) << made.err;
  std::string png;
  for (const auto& e : fs::directory_iterator(dir / "ok" / "frames")) png = e.path().string();
  ASSERT_FALSE(png.empty());
  std::ofstream(dir / "text.png") << "not a picture\n";
  fs::create_directories(dir / "folder.png");
  ASSERT_EQ(::mkfifo((dir / "pipe.png").c_str(), 0600), 0);
  const std::vector<std::pair<std::string, std::string>> compare = {
      {"text.png", "text.png' is not a PNG or a movie"},
      {"folder.png", "folder.png': is a directory"},
      {"pipe.png", "pipe.png': is a pipe"},
      {"none.png", "none.png': no such file"},
  };
  for (const auto& [name, says] : compare) {
    const auto r = grainshock("compare " + png + " " + (dir / name).string());
    EXPECT_EQ(r.exit_code, 2) << name << ": " << r.err;
    EXPECT_EQ(r.err_lines(), 1) << name << ": " << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << name << ": " << r.err;
  }
  // render of a pipe is refused at once (opening it waited for a writer, for ever: the timeout
  // turns a relapse into a failure, not a hung test) and names it.
  const auto p = grainshock("render " + (dir / "pipe.png").string() + " --out " +
                                (dir / "p.png").string(),
                            "timeout 60");
  EXPECT_EQ(p.exit_code, 1) << p.err;
  EXPECT_NE(p.err.find("pipe.png' is a pipe"), std::string::npos) << p.err;

  // A stopped run whose checkpoint became a directory.
  const fs::path stopped = dir / "stopped";
  const pid_t pid = spawn_grainshock(
      "run --dim 3 --medium box --particles 20000 --t-max 1e7 --quiet --out " + stopped.string());
  EXPECT_EQ(interrupt_when(pid, stopped / "checkpoint.bin", SIGINT), 130);
  fs::remove(stopped / "checkpoint.bin");
  fs::remove(stopped / "checkpoint.prev.bin");
  fs::create_directories(stopped / "checkpoint.bin");
  const auto r = grainshock("resume " + stopped.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("checkpoint.bin': is a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("truncated"), std::string::npos) << r.err;
}

// A PNG that cannot be written says why, as the OS says it (libpng's own writer said "Write
// Error" whatever the reason): here a file size limit (ulimit -f, SIGXFSZ ignored).
TEST(CliUsage, PngWriteErrorsSayTheOsReason) {
  const fs::path dir = scratch_dir("pngwrite");
  const auto made = grainshock("run --dim 2 --medium box --particles 200 --t-max 20 --quiet --out " +
                               (dir / "ok").string());
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const auto r = grainshock("render " + (dir / "ok" / "snapshots" / "tsim_20.xyz").string() +
                                " --out " + (dir / "big.png").string(),
                            "ulimit -f 8; trap '' XFSZ;");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("big.png': File too large"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "big.png"));
}

// bench --json into a place it cannot write fails before the first case, not after all of them.
TEST(CliUsage, BenchJsonIsCheckedBeforeTheCases) {
  const fs::path dir = scratch_dir("benchjson");
  const auto r = grainshock("bench sim/ --json " + (dir / "missing" / "b.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("No such file or directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "") << "a case ran before the failure";
}

// Ctrl-C tells the folder to resume, not the placeholder DIR.
TEST(CliUsage, InterruptedRunNamesItsFolderToResume) {
  const fs::path dir = scratch_dir("ctrlc");
  fs::create_directories(dir);
  const fs::path out = dir / "run", err = dir / "err.txt";
  const pid_t pid = spawn_grainshock(
      "run --dim 3 --medium box --particles 20000 --t-max 1e7 --out " + out.string(), err.string());
  EXPECT_EQ(interrupt_when(pid, out / "timeseries.csv", SIGINT), 130);
  const std::string text = read_file(err);
  EXPECT_NE(text.find("(continue with: grainshock resume " + out.string() + ")"),
            std::string::npos)
      << text;
}

// --frame counts as ASE does (-1 the last), and a gzip-compressed snapshot draws as the plain
// one; a .gz cut short, or a frame the file lacks, is one line naming it (exit 1).
TEST(CliUsage, NegativeFramesAndGzipSnapshots) {
  const fs::path dir = scratch_dir("frames");
  const auto run = grainshock(
      "run --medium box --particles 2000 --t-max 100 --snapshot-times 50 --quiet "
      "--trajectory all.xyz --out " +
      dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string all = (dir / "all.xyz").string();
  auto render = [&](const std::string& args, const std::string& png) {
    return grainshock("render " + args + " --width 160 --height 120 --out " +
                      (dir / png).string());
  };
  ASSERT_EQ(render(all + " --frame 1", "f1.png").exit_code, 0);
  ASSERT_EQ(render(all + " --frame -1", "last.png").exit_code, 0);
  ASSERT_EQ(render(all + " --frame -2", "first.png").exit_code, 0);
  ASSERT_EQ(render(all + " --frame 0", "f0.png").exit_code, 0);
  EXPECT_EQ(read_file(dir / "last.png"), read_file(dir / "f1.png"));
  EXPECT_EQ(read_file(dir / "first.png"), read_file(dir / "f0.png"));
  EXPECT_NE(read_file(dir / "f0.png"), read_file(dir / "f1.png"));
  for (const char* k : {"-3", "2"}) {
    const auto r = render(all + " --frame " + k, "none.png");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err_lines(), 1) << r.err;
    EXPECT_NE(r.err.find(std::string("--frame ") + k + ": snapshot '" + all + "' has 2 frames"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "none.png"));

  ASSERT_EQ(std::system(("gzip -k " + all).c_str()), 0);
  ASSERT_EQ(render(all + ".gz --frame -1", "gz.png").exit_code, 0);
  EXPECT_EQ(read_file(dir / "gz.png"), read_file(dir / "f1.png"));
  const std::string bytes = read_file(all + ".gz");
  std::ofstream(dir / "cut.xyz.gz", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const auto r = render((dir / "cut.xyz.gz").string(), "cut.png");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  EXPECT_NE(r.err.find("cut.xyz.gz': cut short"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "cut.png"));
}

// Without a terminal, progress is a plain line every few seconds, the first after half a second
// (before, a run shorter than 5 s printed none): here the first line of a run of minutes.
TEST(CliUsage, ProgressLineWithoutTerminal) {
  const fs::path dir = scratch_dir("progress");
  fs::create_directories(dir);
  const fs::path err = dir / "stderr.txt";
  const pid_t pid = spawn_grainshock(
      "run --dim 3 --medium box --particles 20000 --t-max 1e7 --out " + (dir / "run").string(),
      err.string());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_file(err).find(" elapsed\n") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string text = read_file(err);
  const auto first = text.substr(0, text.find('\n'));
  EXPECT_TRUE(
      std::regex_match(first, std::regex(R"( *\d+\.\d% .*, (ETA \d+ (s|min|h), )?\d+ s elapsed)")))
      << text;
  EXPECT_EQ(text.find('\r'), std::string::npos) << "no terminal, no redrawing";
}

// The completion script names every subcommand and each one's flags, and bash completes with it.
TEST(CliUsage, BashCompletionFromTheCommandTree) {
  const auto r = grainshock("completion bash");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& sub : subcommands())
    EXPECT_NE(r.out.find(" " + sub + ") words=\""), std::string::npos) << sub;
  for (const char* flag : {"--particles", "--t-max", "--restitution", "--tolerance", "--diff",
                           "--realisations", "--version"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;

  const fs::path dir = scratch_dir("completion");
  fs::create_directories(dir);
  const fs::path script = dir / "grainshock.bash";
  std::ofstream(script) << r.out;
  // COMPREPLY for a command line typed so far, from the script run by bash itself.
  auto complete = [&](const std::string& words) {
    const fs::path out = dir / "reply.txt";
    const std::string cmd = "bash -c 'source " + script.string() + " && COMP_WORDS=(" + words +
                            ") && COMP_CWORD=$((${#COMP_WORDS[@]} - 1)) && _grainshock && "
                            "echo \"${COMPREPLY[*]}\"' > " +
                            out.string() + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return read_file(out);
  };
  EXPECT_EQ(complete("grainshock ru"), "run\n");
  EXPECT_EQ(complete("grainshock com"), "compare completion\n");
  EXPECT_EQ(complete("grainshock run --partic"), "--particles\n");
  EXPECT_EQ(complete("grainshock compare --diff x.png --upd"), "--update\n");
  EXPECT_EQ(complete("grainshock render --t-m"), "\n") << "render has no --t-max";
}

}  // namespace
}  // namespace gs::test
