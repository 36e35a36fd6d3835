// Issue 7 crash safety, on both databases (issue 47): a process enrolling users is SIGKILLed at random
// moments; the gallery must open, pass its integrity check and hold every user whose commit the process
// reported. Two processes writing one gallery at once must not corrupt it or lose users.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_backend_test_support.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace bodyrec::store::testing {
namespace {

constexpr int kRounds = 30;

// Child: enrols users with two views each (one transaction per user) and reports each committed id on
// `fd`; never returns.
[[noreturn]] void enrol_forever(const std::string& path, int fd, int seed) {
  try {
    GalleryOptions o;
    o.create = true;
    Gallery g(path, o);
    for (int i = 0;; ++i) {
      UserId id = 0;
      g.transaction([&] {
        id = g.enrol(make_scan(View::F, 0.5, seed + i, 160, 80));
        g.put_scan(id, make_scan(View::B, 0.5, seed + i + 1, 160, 80));
      });
      if (::write(fd, &id, sizeof(id)) != sizeof(id)) ::_exit(2);
    }
  } catch (...) {
    ::_exit(1);
  }
}

TEST_P(GalleryCrashSafety, SigkillDuringEnrolmentNeverLosesACommittedUser) {
  const std::string path = fresh();
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> delay_us(0, 250000);
  std::set<UserId> reported;
  int killed_running = 0;
  for (int round = 0; round < kRounds; ++round) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(fds[0]);
      enrol_forever(path, fds[1], round * 1000);
    }
    ::close(fds[1]);
    // Odd rounds: a random moment after fork (may hit file creation, schema or the first enrolment).
    // Even rounds: wait for the first reported commit, then a random moment (mid-enrolment, whatever
    // the machine's load).
    UserId id = 0;
    if (round % 2 == 0 && ::read(fds[0], &id, sizeof(id)) == sizeof(id)) reported.insert(id);
    std::this_thread::sleep_for(std::chrono::microseconds(round % 2 == 0 ? delay_us(rng) / 8 : delay_us(rng)));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) ++killed_running;
    while (::read(fds[0], &id, sizeof(id)) == sizeof(id)) reported.insert(id);
    ::close(fds[0]);

    if (!postgres() && !std::filesystem::exists(path)) continue;  // killed before it created the file
    // As the pipeline reopens it after a crash (a kill between creating the file and committing the
    // schema leaves an empty file, which create=true initialises).
    GalleryOptions o;
    o.create = true;
    Gallery g(path, o);
    ASSERT_EQ(g.integrity_check(), "ok") << "round " << round;
    for (UserId u : reported) {
      const auto user = g.user(u);
      ASSERT_TRUE(user) << "round " << round << ": committed user " << u << " lost";
      EXPECT_EQ(user->scans, 2) << "round " << round << ": user " << u << " half-enrolled";
    }
    // Nothing half-written either: every user in the file has both views.
    for (const User& u : g.users()) EXPECT_EQ(u.scans, 2) << "round " << round << ": user " << u.id;
  }
  EXPECT_EQ(killed_running, kRounds);
  EXPECT_GE(reported.size(), static_cast<size_t>(kRounds / 2));  // at least one per even round
  std::printf("[ crash    ] %d SIGKILL rounds, %zu committed users reported, all present, integrity ok\n",
              kRounds, reported.size());
}

TEST_P(GalleryCrashSafety, TwoProcessesWritingOneGalleryLoseNothing) {
  const std::string path = fresh();
  { Gallery g(path, creating()); }
  constexpr int kPerProcess = 40;
  std::vector<pid_t> children;
  for (int p = 0; p < 2; ++p) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        Gallery g(path);
        for (int i = 0; i < kPerProcess; ++i) {
          const UserId id = g.enrol(make_scan(View::F, 0.5, p * 100 + i), std::string(1, 'a' + p) + std::to_string(i));
          Event e;
          e.user = id;
          e.kind = EventKind::kRecognised;
          e.score = i;
          g.log_event(e);
          g.refresh();
        }
        ::_exit(0);
      } catch (...) {
        ::_exit(1);
      }
    }
    children.push_back(child);
  }
  for (pid_t child : children) {
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a writer failed (busy timeout?)";
  }
  Gallery g(path);
  EXPECT_EQ(g.integrity_check(), "ok");
  EXPECT_EQ(g.user_count(), 2 * kPerProcess);
  EXPECT_EQ(g.events().size(), 4u * kPerProcess);
  EXPECT_EQ(g.scans(View::F).size(), 2u * kPerProcess);
  for (int p = 0; p < 2; ++p)
    for (int i = 0; i < kPerProcess; ++i) EXPECT_NO_THROW(g.resolve_user(std::string(1, 'a' + p) + std::to_string(i)));
}

}  // namespace
}  // namespace bodyrec::store::testing
