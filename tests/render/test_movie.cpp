// The movie writer, checked by decoding what it wrote with libavformat/libavcodec.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
}

#include "render/movie_parts.h"
#include "render/movie_writer.h"
#include "sim/error.h"
#include "sim/stop.h"
#include "tests/render/movie_decode.h"

extern char** environ;

namespace gs::render {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(GRAINSHOCK_TEST_OUTPUT_DIR) / "movie" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename());
  return out;
}

// Frame `k` of a test scene: a smooth gradient and five coloured discs, antialiased as the
// renderer draws them, moving 3 px per frame in different directions, so that consecutive frames
// differ and a frame can be told from its neighbours.
Image scene(int w, int h, int k) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(20 + 60 * x / w);
      p[1] = static_cast<std::uint8_t>(20 + 40 * y / h);
      p[2] = static_cast<std::uint8_t>(60 + 80 * (x + y) / (w + h));
      p[3] = 255;
    }
  const double colours[5][3] = {
      {230, 40, 40}, {40, 220, 60}, {50, 80, 240}, {250, 220, 40}, {240, 240, 240}};
  const double r = h / 8.0;
  for (int d = 0; d < 5; ++d) {
    const double angle = 1.3 * d;
    const double cx = std::fmod(w * (0.15 + 0.17 * d) + 3.0 * k * std::cos(angle) + 4 * w, w);
    const double cy = std::fmod(h * (0.2 + 0.15 * d) + 3.0 * k * std::sin(angle) + 4 * h, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double cover = std::clamp(r + 0.5 - std::hypot(x - cx, y - cy), 0.0, 1.0);
        for (int c = 0; c < 3; ++c) {
          std::uint8_t& v = img.pixel(x, y)[c];
          v = static_cast<std::uint8_t>(std::lround(v * (1 - cover) + colours[d][c] * cover));
        }
      }
  }
  return img;
}

Image flat(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
  return img;
}

void write_scene(const fs::path& path, const MovieOptions& o, int frames) {
  MovieWriter movie(path, o);
  for (int k = 0; k < frames; ++k) movie.add(scene(o.width, o.height, k));
  movie.finish();
}

// yuv420p keeps one chroma sample per 2x2 pixels (and 8-bit limited-range luma), so saturated disc
// edges lose colour: the conversion round trip alone gives about 35 dB on this scene and CRF 18
// costs little more. 30 dB (RMS error 8 of 255) is the bound we hold it to; the neighbouring frame
// gives about 20 dB (the negative controls below), and the colour matrix is checked exactly
// elsewhere.
constexpr double kMinPsnr = 30.0;

TEST(MovieWriter, H264ByDefaultWithRequestedTimingAndBt709Tags) {
  const auto dir = fresh_dir("h264");
  MovieOptions o;
  o.width = 320;
  o.height = 240;
  o.fps = 24;
  const int n = 48;
  {
    MovieWriter movie(dir / "movie.mp4", o);
    const bool have_x264 = avcodec_find_encoder_by_name("libx264") != nullptr;
    EXPECT_EQ(movie.encoder_name(), have_x264 ? "libx264" : "mpeg4");
    for (int k = 0; k < n; ++k) movie.add(scene(o.width, o.height, k));
    EXPECT_FALSE(fs::exists(dir / "movie.mp4")) << "the final name appears only when complete";
    movie.finish();
  }
  EXPECT_EQ(files_in(dir), std::vector<fs::path>{"movie.mp4"}) << "no temporary file left behind";

  const int k = 17;
  const Decoded d = decode_movie(dir / "movie.mp4", k);
  EXPECT_EQ(d.codec, AV_CODEC_ID_H264);
  EXPECT_EQ(d.width, 320);
  EXPECT_EQ(d.height, 240);
  EXPECT_EQ(d.frames, n);
  EXPECT_EQ(d.nb_frames, n);
  EXPECT_EQ(av_cmp_q(d.avg_frame_rate, AVRational{24, 1}), 0);
  EXPECT_EQ(av_cmp_q(d.r_frame_rate, AVRational{24, 1}), 0);
  EXPECT_NEAR(d.duration, n / 24.0, 1e-3);
  EXPECT_EQ(d.range, AVCOL_RANGE_MPEG);
  EXPECT_EQ(d.space, AVCOL_SPC_BT709);
  EXPECT_EQ(d.primaries, AVCOL_PRI_BT709);
  EXPECT_EQ(d.trc, AVCOL_TRC_BT709);

  ASSERT_EQ(d.rgb.width, 320);
  EXPECT_GE(psnr(d.rgb, scene(320, 240, k), 320, 240), kMinPsnr);
  // Negative control: the test tells frame k from its neighbours.
  EXPECT_LT(psnr(d.rgb, scene(320, 240, k + 2), 320, 240), kMinPsnr);
}

TEST(MovieWriter, FaststartPutsTheIndexFirst) {
  const auto dir = fresh_dir("faststart");
  MovieOptions o;
  o.width = 64;
  o.height = 48;
  write_scene(dir / "movie.mp4", o, 10);
  // MP4 top-level boxes: size (4 bytes, big endian), type (4 bytes). moov must precede mdat.
  std::FILE* f = std::fopen((dir / "movie.mp4").c_str(), "rb");
  ASSERT_TRUE(f);
  std::vector<std::string> boxes;
  unsigned char head[8];
  long pos = 0;
  while (std::fseek(f, pos, SEEK_SET) == 0 && std::fread(head, 1, 8, f) == 8) {
    const long size =
        (long(head[0]) << 24) | (long(head[1]) << 16) | (long(head[2]) << 8) | head[3];
    boxes.emplace_back(reinterpret_cast<char*>(head + 4), 4);
    if (size < 8) break;
    pos += size;
  }
  std::fclose(f);
  const auto moov = std::find(boxes.begin(), boxes.end(), "moov");
  const auto mdat = std::find(boxes.begin(), boxes.end(), "mdat");
  ASSERT_NE(moov, boxes.end());
  ASSERT_NE(mdat, boxes.end());
  EXPECT_LT(moov - boxes.begin(), mdat - boxes.begin());
}

// Limited-range BT.709 luma of pure colours: Y = 16 + 219 (0.2126 R + 0.7152 G + 0.0722 B).
// BT.601 would give 82 for red and 145 for green instead of 63 and 173.
TEST(MovieWriter, ConvertsWithBt709LimitedRange) {
  const auto dir = fresh_dir("bt709");
  MovieOptions o;
  o.width = 64;
  o.height = 48;
  o.crf = 0;  // lossless x264, so only the colour conversion is measured (mpeg4 stays near)
  {
    MovieWriter movie(dir / "movie.mp4", o);
    movie.add(flat(64, 48, 255, 0, 0));
    movie.add(flat(64, 48, 0, 255, 0));
    movie.add(flat(64, 48, 255, 255, 255));
    movie.add(flat(64, 48, 0, 0, 0));
    movie.finish();
  }
  const Decoded d = decode_movie(dir / "movie.mp4");
  ASSERT_EQ(d.centre_luma.size(), 4u);
  EXPECT_NEAR(d.centre_luma[0], 63, 2);
  EXPECT_NEAR(d.centre_luma[1], 173, 2);
  EXPECT_NEAR(d.centre_luma[2], 235, 2);
  EXPECT_NEAR(d.centre_luma[3], 16, 2);
}

TEST(MovieWriter, OddSizesArePaddedByRepeatingTheEdge) {
  const auto dir = fresh_dir("odd");
  MovieOptions o;
  o.width = 321;
  o.height = 241;
  o.fps = 25;
  {
    MovieWriter movie(dir / "movie.mp4", o);
    EXPECT_EQ(movie.encoded_width(), 322);
    EXPECT_EQ(movie.encoded_height(), 242);
    for (int k = 0; k < 10; ++k) movie.add(scene(o.width, o.height, k));
    movie.finish();
  }
  const Decoded d = decode_movie(dir / "movie.mp4", 5);
  EXPECT_EQ(d.width, 322);
  EXPECT_EQ(d.height, 242);
  EXPECT_EQ(d.frames, 10);
  ASSERT_EQ(d.rgb.width, 322);
  const Image src = scene(o.width, o.height, 5);
  EXPECT_GE(psnr(d.rgb, src, o.width, o.height), kMinPsnr);
  // The added column and row repeat the picture's last ones (not black).
  double diff = 0;
  for (int y = 0; y < o.height; ++y)
    for (int c = 0; c < 3; ++c) diff += std::abs(d.rgb.pixel(321, y)[c] - src.pixel(320, y)[c]);
  for (int x = 0; x < o.width; ++x)
    for (int c = 0; c < 3; ++c) diff += std::abs(d.rgb.pixel(x, 241)[c] - src.pixel(x, 240)[c]);
  EXPECT_LT(diff / (3.0 * (o.width + o.height)), 8.0);
}

TEST(MovieWriter, Mpeg4FallbackCodec) {
  const auto dir = fresh_dir("mpeg4");
  MovieOptions o;
  o.codec = "mpeg4";
  o.width = 320;
  o.height = 240;
  o.fps = 30;
  const int n = 45;
  {
    MovieWriter movie(dir / "movie.mp4", o);
    EXPECT_EQ(movie.encoder_name(), "mpeg4");
    for (int k = 0; k < n; ++k) movie.add(scene(o.width, o.height, k));
    movie.finish();
  }
  const int k = 40;
  const Decoded d = decode_movie(dir / "movie.mp4", k);
  EXPECT_EQ(d.codec, AV_CODEC_ID_MPEG4);
  EXPECT_EQ(d.width, 320);
  EXPECT_EQ(d.height, 240);
  EXPECT_EQ(d.frames, n);
  EXPECT_EQ(av_cmp_q(d.avg_frame_rate, AVRational{30, 1}), 0);
  EXPECT_NEAR(d.duration, n / 30.0, 1e-3);
  ASSERT_EQ(d.rgb.width, 320);
  EXPECT_GE(psnr(d.rgb, scene(320, 240, k), 320, 240), kMinPsnr);
  EXPECT_LT(psnr(d.rgb, scene(320, 240, k - 2), 320, 240), kMinPsnr);
}

TEST(MovieWriter, StopSignalFinishesAPlayableMovie) {
  const auto dir = fresh_dir("stop_flag");
  MovieOptions o;
  o.width = 96;
  o.height = 64;
  gs::clear_stop();
  gs::install_stop_handlers();
  int written = 0;
  {
    MovieWriter movie(dir / "movie.mp4", o);
    for (int k = 0; k < 1000 && !gs::stop_requested(); ++k) {
      movie.add(scene(o.width, o.height, k));
      ++written;
      if (k == 29) std::raise(SIGTERM);  // a real signal, caught by the handler
    }
    movie.finish();
  }
  EXPECT_EQ(gs::stop_signal(), SIGTERM);
  gs::clear_stop();
  EXPECT_EQ(written, 30);
  const Decoded d = decode_movie(dir / "movie.mp4");
  EXPECT_EQ(d.frames, 30);
  EXPECT_NEAR(d.duration, 30 / 30.0, 1e-3);
}

struct Child {
  pid_t pid = -1;
  std::FILE* out = nullptr;  // the child's stdout
};

Child spawn_helper(const fs::path& movie) {
  int fds[2];
  EXPECT_EQ(pipe(fds), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  std::string helper = MOVIE_STOP_HELPER, arg = movie.string();
  char* argv[] = {helper.data(), arg.data(), nullptr};
  Child c;
  EXPECT_EQ(posix_spawn(&c.pid, helper.c_str(), &actions, nullptr, argv, environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  c.out = fdopen(fds[0], "r");
  return c;
}

std::string read_line(std::FILE* f) {
  char buf[256];
  return std::fgets(buf, sizeof buf, f) ? std::string(buf) : std::string();
}

TEST(MovieWriter, ChildKilledWithSigtermLeavesAPlayableMovie) {
  const auto dir = fresh_dir("sigterm");
  Child c = spawn_helper(dir / "movie.mp4");
  ASSERT_EQ(read_line(c.out), "ready\n");
  ASSERT_EQ(kill(c.pid, SIGTERM), 0);
  const std::string last = read_line(c.out);
  std::fclose(c.out);
  int status = 0;
  ASSERT_EQ(waitpid(c.pid, &status, 0), c.pid);
  ASSERT_TRUE(WIFEXITED(status)) << "the helper died of the signal instead of finishing";
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  int frames = -1;
  ASSERT_EQ(std::sscanf(last.c_str(), "frames %d", &frames), 1) << last;
  EXPECT_GE(frames, 20);
  EXPECT_EQ(files_in(dir), std::vector<fs::path>{"movie.mp4"});
  const Decoded d = decode_movie(dir / "movie.mp4");
  EXPECT_EQ(d.frames, frames);
  EXPECT_NEAR(d.duration, frames / 30.0, 1e-3);
}

TEST(MovieWriter, ChildKilledOutrightLeavesNoMovie) {
  const auto dir = fresh_dir("sigkill");
  Child c = spawn_helper(dir / "movie.mp4");
  ASSERT_EQ(read_line(c.out), "ready\n");
  ASSERT_EQ(kill(c.pid, SIGKILL), 0);
  std::fclose(c.out);
  int status = 0;
  ASSERT_EQ(waitpid(c.pid, &status, 0), c.pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  // Only the hidden temporary file can be there; nothing named movie.mp4 pretends to be a movie.
  EXPECT_FALSE(fs::exists(dir / "movie.mp4"));
}

TEST(MovieWriter, UnknownCodecIsAUserErrorAndLeavesNoFile) {
  const auto dir = fresh_dir("unknown_codec");
  MovieOptions o;
  o.codec = "vp13";
  o.width = 64;
  o.height = 48;
  try {
    MovieWriter movie(dir / "movie.mp4", o);
    FAIL() << "no error for an unknown codec";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("vp13"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  EXPECT_TRUE(files_in(dir).empty());
}

TEST(MovieWriter, UnwritablePathIsAUserErrorAndLeavesNoFile) {
  const auto dir = fresh_dir("unwritable");
  MovieOptions o;
  o.width = 64;
  o.height = 48;
  const fs::path path = dir / "missing-folder" / "movie.mp4";
  try {
    MovieWriter movie(path, o);
    FAIL() << "no error for a path in a missing folder";
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find("No such file or directory"), std::string::npos) << what;
  }
  EXPECT_TRUE(files_in(dir).empty());
}

TEST(MovieWriter, BadOptionsAreUserErrors) {
  const auto dir = fresh_dir("bad_options");
  auto opens = [&](const MovieOptions& o, const std::string& name = "movie.mp4") {
    try {
      MovieWriter movie(dir / name, o);
      movie.discard();
      return true;
    } catch (const UserError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      return false;
    }
  };
  MovieOptions good;
  good.width = 64;
  good.height = 48;
  EXPECT_TRUE(opens(good));
  MovieOptions o = good;
  for (double fps : {0.0, -5.0, double(NAN), double(INFINITY)}) {
    o.fps = fps;
    EXPECT_FALSE(opens(o)) << "fps " << fps;
  }
  o = good;
  o.crf = 52;
  EXPECT_FALSE(opens(o));
  o = good;
  o.width = 0;
  EXPECT_FALSE(opens(o));
  if (avcodec_find_encoder_by_name("libx264")) {  // mpeg4 has no presets
    o = good;
    o.preset = "warp";
    EXPECT_FALSE(opens(o));
  }
  o = good;
  o.codec = "";
  EXPECT_FALSE(opens(o));
  EXPECT_FALSE(opens(good, "movie.unknownext"));
  EXPECT_TRUE(files_in(dir).empty());
}

TEST(MovieWriter, ExceptionWhileWritingRemovesThePartialFile) {
  const auto dir = fresh_dir("exception");
  MovieOptions o;
  o.width = 64;
  o.height = 48;
  try {
    MovieWriter movie(dir / "movie.mp4", o);
    for (int k = 0; k < 10; ++k) movie.add(scene(64, 48, k));
    throw std::runtime_error("the simulation failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(files_in(dir).empty());
}

TEST(MovieWriter, DiscardLeavesNoFileAndDestructorFinishes) {
  const auto dir = fresh_dir("discard");
  MovieOptions o;
  o.width = 64;
  o.height = 48;
  {
    MovieWriter movie(dir / "discarded.mp4", o);
    for (int k = 0; k < 5; ++k) movie.add(scene(64, 48, k));
    movie.discard();
  }
  EXPECT_TRUE(files_in(dir).empty());
  {
    MovieWriter movie(dir / "kept.mp4", o);
    for (int k = 0; k < 7; ++k) movie.add(scene(64, 48, k));
  }
  EXPECT_EQ(files_in(dir), std::vector<fs::path>{"kept.mp4"});
  EXPECT_EQ(decode_movie(dir / "kept.mp4").frames, 7);
}

// Frames of `sizes` parts, cut after each, of the test scene numbered on from `first`.
void add_parts(MovieParts& movie, const MovieOptions& o, const std::vector<int>& sizes,
               int first = 0) {
  int k = first;
  for (int n : sizes) {
    for (int j = 0; j < n; ++j) movie.add(scene(o.width, o.height, k++));
    movie.cut();
  }
}

MovieOptions small_movie(const std::string& codec = "h264") {
  MovieOptions o;
  o.width = 160;
  o.height = 120;
  o.fps = 24;
  o.codec = codec;
  return o;
}

// Parts of one frame, of two and of more than a group of B-frames: the joined movie plays every
// frame once, in order and at its time, for both codecs.
TEST(MovieParts, JoinedPartsPlayAsOneMovie) {
  for (const std::string codec : {"h264", "mpeg4"}) {
    const auto dir = fresh_dir("parts_" + codec);
    const MovieOptions o = small_movie(codec);
    const std::vector<int> sizes = {1, 2, 7, 1, 5};
    const int n = 16;
    {
      MovieParts movie(dir / "movie.mp4", o);
      add_parts(movie, o, sizes);
      EXPECT_EQ(movie.parts(), 5);
      EXPECT_EQ(movie.frames_added(), n);
      EXPECT_TRUE(movie.finish());
    }
    EXPECT_EQ(files_in(dir), std::vector<fs::path>{"movie.mp4"}) << "the parts are removed";
    for (int k = 0; k < n; ++k) {
      const Decoded d = decode_movie(dir / "movie.mp4", k);
      ASSERT_EQ(d.frames, n) << codec;
      EXPECT_EQ(d.nb_frames, n);
      EXPECT_NEAR(d.duration, n / 24.0, 1e-3);
      EXPECT_EQ(av_cmp_q(d.avg_frame_rate, AVRational{24, 1}), 0);
      ASSERT_EQ(d.rgb.width, 160);
      EXPECT_GE(psnr(d.rgb, scene(160, 120, k), 160, 120), kMinPsnr) << codec << " frame " << k;
      // Frame k is not its neighbour: the parts are joined in order.
      EXPECT_LT(psnr(d.rgb, scene(160, 120, k + 2), 160, 120), kMinPsnr) << codec << " " << k;
    }
  }
}

// An uncut movie is renamed, not joined: the same bytes as one MovieWriter writes.
TEST(MovieParts, OnePartIsTheMovieOfOneWriter) {
  const auto dir = fresh_dir("parts_one");
  const MovieOptions o = small_movie();
  write_scene(dir / "writer.mp4", o, 9);
  {
    MovieParts movie(dir / "parts.mp4", o);
    for (int k = 0; k < 9; ++k) movie.add(scene(o.width, o.height, k));
    movie.finish();
  }
  auto bytes = [](const fs::path& p) {
    std::FILE* f = std::fopen(p.c_str(), "rb");
    std::string s;
    for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
    std::fclose(f);
    return s;
  };
  EXPECT_EQ(bytes(dir / "writer.mp4"), bytes(dir / "parts.mp4"));
  EXPECT_FALSE(fs::exists(MovieParts::folder(dir / "parts.mp4")));
}

// Going on after two parts, as a resume does: what a kill left after them (a third part and a
// partial fourth) is removed, and the movie ends as if never stopped.
TEST(MovieParts, GoesOnAfterTheCheckpointedParts) {
  const auto dir = fresh_dir("parts_resume");
  const MovieOptions o = small_movie();
  {
    MovieParts movie(dir / "movie.mp4", o);
    add_parts(movie, o, {3, 4, 2});
    movie.add(scene(o.width, o.height, 9));
    movie.keep();
    // A kill: the writer of the open part never finishes, its temporary file stays.
    std::ofstream(MovieParts::folder(dir / "movie.mp4") / ".part_0003.mp4.999.partial") << "x";
  }
  {
    MovieParts movie(dir / "movie.mp4", o, 2, 7);
    const fs::path parts = MovieParts::folder(dir / "movie.mp4");
    EXPECT_FALSE(fs::exists(parts / "part_0002.mp4"));
    EXPECT_FALSE(fs::exists(parts / ".part_0003.mp4.999.partial"));
    EXPECT_TRUE(fs::exists(parts / "part_0001.mp4"));
    add_parts(movie, o, {5}, 7);
    EXPECT_EQ(movie.frames_added(), 12);
    movie.finish();
  }
  for (int k : {0, 6, 7, 11}) {
    const Decoded d = decode_movie(dir / "movie.mp4", k);
    ASSERT_EQ(d.frames, 12);
    EXPECT_GE(psnr(d.rgb, scene(160, 120, k), 160, 120), kMinPsnr) << "frame " << k;
  }
  // A checkpoint naming a part that is gone is refused.
  EXPECT_THROW(MovieParts(dir / "movie.mp4", o, 1, 3), UserError);
}

// Parts of keyint frames, each encoded alone: a movie cut at a part's end (a checkpoint) and one
// resumed there are the very bytes of one never cut; the encode is the same every time.
TEST(MovieParts, PartsOfKeyintFramesMakeTheSameBytesWhereverCut) {
  const auto dir = fresh_dir("parts_keyint");
  MovieOptions o = small_movie();
  o.keyint = 4;
  auto bytes = [](const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  for (const char* name : {"a.mp4", "b.mp4"}) {
    MovieParts movie(dir / name, o);
    for (int k = 0; k < 10; ++k) movie.add(scene(o.width, o.height, k));
    EXPECT_EQ(movie.parts(), 2);  // the third is open
    movie.finish();
  }
  {
    MovieParts movie(dir / "cut.mp4", o);
    for (int k = 0; k < 8; ++k) movie.add(scene(o.width, o.height, k));
    movie.cut();
    movie.keep();
  }
  {
    MovieParts movie(dir / "cut.mp4", o, 2, 8);
    for (int k = 8; k < 10; ++k) movie.add(scene(o.width, o.height, k));
    movie.finish();
  }
  const std::string a = bytes(dir / "a.mp4");
  EXPECT_EQ(decode_movie(dir / "a.mp4").frames, 10);
  EXPECT_TRUE(a == bytes(dir / "b.mp4")) << "two encodes of the same frames differ";
  EXPECT_TRUE(a == bytes(dir / "cut.mp4")) << "a movie resumed at a part's end differs";
}

// A movie going on from parts on disk whose join is refused (a part spoiled meanwhile) keeps
// every part: they are not made again by this process.
TEST(MovieParts, ARefusedJoinOfAResumedMovieKeepsTheParts) {
  const auto dir = fresh_dir("parts_refused");
  const MovieOptions o = small_movie();
  const fs::path parts = MovieParts::folder(dir / "movie.mp4");
  {
    MovieParts movie(dir / "movie.mp4", o);
    add_parts(movie, o, {3, 4});
    movie.keep();
  }
  {
    MovieParts movie(dir / "movie.mp4", o, 2, 7);
    add_parts(movie, o, {2}, 7);
    std::ofstream(parts / "part_0000.mp4", std::ios::trunc) << "spoiled";
    EXPECT_THROW(movie.finish(), UserError);
  }
  EXPECT_FALSE(fs::exists(dir / "movie.mp4"));
  for (const char* name : {"part_0000.mp4", "part_0001.mp4", "part_0002.mp4"})
    EXPECT_TRUE(fs::exists(parts / name)) << name;
}

TEST(MovieParts, PartsOfOtherSettingsAreNotJoined) {
  const auto dir = fresh_dir("parts_mismatch");
  MovieOptions a = small_movie(), b = small_movie();
  b.width = 128;
  write_scene(dir / "a.mp4", a, 3);
  write_scene(dir / "b.mp4", b, 3);
  EXPECT_THROW(join_movies({dir / "a.mp4", dir / "b.mp4"}, dir / "ab.mp4"), UserError);
  EXPECT_FALSE(fs::exists(dir / "ab.mp4"));
  std::ofstream(dir / "junk.mp4") << "not a movie";
  EXPECT_THROW(join_movies({dir / "a.mp4", dir / "junk.mp4"}, dir / "aj.mp4"), UserError);
  EXPECT_EQ(files_in(dir).size(), 3u) << "no temporary left";
}

}  // namespace
}  // namespace gs::render
