#ifndef talus_io_checkpointing_h
#define talus_io_checkpointing_h

#include <talus/base/input.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <boost/archive/archive_exception.hpp>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>

#include <chrono>
#include <fstream>
#include <functional>
#include <map>
#include <string>

namespace Talus
{
  namespace IO
  {
    /**
     * Checkpoints of a run on disk (subsection `Checkpoint`): when they are
     * due (every N steps and/or every T minutes of wall time), how they
     * are written (atomically: into a new directory `tmp-checkpoint-N`,
     * which is renamed to `checkpoint-N` once every file is complete and
     * flushed; a crash during a write leaves the previous checkpoints
     * untouched), how many are kept (the last k), and how the newest one
     * is found and checked on resume.
     *
     * What goes into a checkpoint is written by the caller into the
     * directory handed to the writer of write() (the MPM problem:
     * MPM::MPMProblem::save_checkpoint(); the time loop: its own archive).
     * Every checkpoint directory ends with a `manifest`, written last: the
     * format name and version, the step, time, reason, number of ranks
     * and parameter file, and every file with its size and
     * CRC-32. read_manifest() checks them all, so that a truncated,
     * damaged or foreign checkpoint is rejected with a message that names
     * the file and what is wrong, before anything is loaded.
     *
     * The class does not depend on the space dimension.
     */
    class Checkpointing
    {
    public:
      /** Format name in the first line of every manifest. */
      static const std::string format_name;
      /** Version of the checkpoint format (manifest line 1). */
      static constexpr unsigned int format_version = 10;

      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Parse subsection `Checkpoint`; an empty `directory` means
       * <@p output_directory>/checkpoints.
       */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &output_directory);

      /** Whether checkpoints are written at all (by steps or wall time). */
      bool
      enabled() const
      {
        return every_steps > 0 || every_minutes > 0.;
      }

      /**
       * The problem the checkpoints belong to (`mpm`, the default, or
       * `coupled`), written into the manifest as the key `problem` and
       * checked by find_and_check().
       */
      void
      set_problem(const std::string &name)
      {
        problem = name;
      }

      /** Whether `resume = true` was set in the file. */
      bool
      resume_requested() const
      {
        return resume;
      }

      /** The directory holding the checkpoint-N subdirectories. */
      const std::string &
      directory() const
      {
        return checkpoint_directory;
      }

      /**
       * Whether a checkpoint is due after step @p step: every `every
       * steps` steps, or when `every minutes` of wall time have passed
       * since the start or the last checkpoint (rank 0's clock, the same
       * answer on every rank). Collective.
       */
      bool
      due(const unsigned int step, const MPI_Comm communicator) const;

      /**
       * Whether the run must stop after this step: `stop after minutes`
       * of wall time have passed since the start (rank 0's clock, the
       * same answer on every rank; never with `stop after minutes` = 0).
       * The time loop then writes a checkpoint and stops with an error
       * naming it, also if checkpoints are not written otherwise.
       * Collective.
       */
      bool
      stop_due(const MPI_Comm communicator) const;

      /** The value of `stop after minutes` [min] (0: no limit). */
      double
      stop_minutes() const
      {
        return stop_after_minutes;
      }

      /**
       * The message of a run stopped at its wall-time limit after step
       * @p step at time @p time [s], its state in the checkpoint
       * @p path.
       */
      std::string
      wall_limit_message(const unsigned int step,
                         const double       time,
                         const std::string &path) const;

      /**
       * What a run stopped by lost material points ('abort on lost
       * material points') adds to its message: the state after step
       * @p step, without the lost points, is in the checkpoint @p path,
       * and how to resume from it.
       */
      static std::string
      lost_points_note(const unsigned int step, const std::string &path);

      /**
       * Write checkpoint number @p step at time @p time: make
       * `tmp-checkpoint-<step>`, let @p writer (collective) put its files
       * there, write the manifest with the step, time, @p reason, number
       * of ranks and parameter file and the files' sizes and checksums,
       * flush everything
       * to disk, rename the directory to `checkpoint-<step>` (replacing
       * one of the same number), and delete all but the newest `keep`
       * checkpoints. Returns the path of the new checkpoint. Collective.
       */
      std::string
      write(const unsigned int                                       step,
            const double                                             time,
            const std::string                                       &reason,
            const std::function<void(const std::string &directory)> &writer,
            const MPI_Comm communicator);

      /**
       * Write the boost binary archive @p filename: the string @p tag,
       * then whatever @p serializer(archive) writes.
       */
      template <class Serializer>
      static void
      save_archive(const std::string &filename,
                   const std::string &tag,
                   const Serializer  &serializer)
      {
        std::ofstream                   out(filename, std::ios::binary);
        boost::archive::binary_oarchive archive(out);
        std::string                     name = tag;
        archive << name;
        serializer(archive);
      }

      /**
       * Read the archive @p filename of save_archive() in checkpoint
       * @p checkpoint with @p serializer(archive), after checking its
       * @p tag. Throws ExcInvalidInput naming the file if it is not such
       * an archive or cannot be read.
       */
      template <class Serializer>
      static void
      load_archive(const std::string &checkpoint,
                   const std::string &filename,
                   const std::string &tag,
                   const Serializer  &serializer)
      {
        const std::string start = "Cannot resume from the checkpoint <" +
                                  checkpoint + ">: the file <" + filename +
                                  "> ";
        std::ifstream in(filename, std::ios::binary);
        if (!in)
          throw ExcInvalidInput(start + "cannot be opened.");
        try
          {
            boost::archive::binary_iarchive archive(in);
            std::string                     name;
            archive >> name;
            if (name != tag)
              throw ExcInvalidInput(start + "is not a '" + tag + "' archive.");
            serializer(archive);
          }
        catch (const boost::archive::archive_exception &e)
          {
            throw ExcInvalidInput(start + "cannot be read (" + e.what() + ").");
          }
      }

      /**
       * The checkpoint to resume from given @p path: @p path itself if it
       * holds a manifest, else the complete checkpoint-N in @p path with the
       * largest N. Throws ExcInvalidInput if there is none.
       */
      static std::string
      find_newest(const std::string &path);

      /**
       * Read and check the manifest of checkpoint @p path: format name and
       * version, every listed file present with its size and CRC-32.
       * Returns the key-value pairs. Throws ExcInvalidInput naming the
       * file and the problem.
       */
      static std::map<std::string, std::string>
      read_manifest(const std::string &path);

      /**
       * find_newest() and read_manifest() on rank 0, and that the
       * checkpoint belongs to a run of @p problem (the manifest's key
       * `problem`; `mpm` without it); the result (or the error, thrown on
       * every rank) shared with all ranks. Collective.
       */
      static std::string
      find_and_check(const std::string &path,
                     const MPI_Comm     communicator,
                     const std::string &problem = "mpm");

    private:
      unsigned int every_steps        = 0;
      double       every_minutes      = 0.;
      double       stop_after_minutes = 0.;
      unsigned int keep               = 2;
      bool         resume             = false;
      std::string  checkpoint_directory;
      std::string  problem = "mpm";
      /** Wall clock of the start or the last checkpoint (rank 0). */
      std::chrono::steady_clock::time_point last_write =
        std::chrono::steady_clock::now();
      /** Wall clock of the start (rank 0). */
      std::chrono::steady_clock::time_point start =
        std::chrono::steady_clock::now();
    };
  } // namespace IO
} // namespace Talus

#endif
