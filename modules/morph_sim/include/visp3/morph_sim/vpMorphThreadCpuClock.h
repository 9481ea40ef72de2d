/*!
  \file vpMorphThreadCpuClock.h
  \brief A std::chrono clock over the CPU time of the calling thread, for timing code under parallel runs.
*/
#ifndef VP_MORPH_THREAD_CPU_CLOCK_H
#define VP_MORPH_THREAD_CPU_CLOCK_H

#include <chrono>
#include <ctime>

/*!
  \class vpMorphThreadCpuClock
  \ingroup group_morph_sim
  \brief The CPU time the calling thread has used (POSIX CLOCK_THREAD_CPUTIME_ID), as a std::chrono clock.

  Why: with runs on every core, wall time also counts the periods a run waits while another one has the core. The
  CPU time of the thread that computes is the cost of the code itself, comparable with Google Benchmark's CPU time.
  Only differences between two now() of one thread mean anything.
  \code
  const vpMorphThreadCpuClock::time_point t0 = vpMorphThreadCpuClock::now();
  // ... work ...
  const double ms = vpMorphThreadCpuClock::millisecondsSince(t0);
  \endcode
*/
class vpMorphThreadCpuClock
{
public:
  //! Nanoseconds (std::chrono clock requirements).
  typedef std::chrono::nanoseconds duration;
  //! Tick count type.
  typedef duration::rep rep;
  //! Tick period.
  typedef duration::period period;
  //! A point in this thread's CPU time.
  typedef std::chrono::time_point<vpMorphThreadCpuClock> time_point;
  //! A thread's CPU time never goes back.
  static constexpr bool is_steady = true;

  //! The calling thread's CPU time so far.
  static time_point now() noexcept
  {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return time_point(duration(static_cast<rep>(ts.tv_sec) * 1000000000 + static_cast<rep>(ts.tv_nsec)));
  }
  //! Milliseconds of this thread's CPU time since \e t0 (taken by now() on the same thread).
  static double millisecondsSince(time_point t0) noexcept
  {
    return std::chrono::duration<double, std::milli>(now() - t0).count();
  }
};

#endif
