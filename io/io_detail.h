/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file io_detail.h
 * \brief What the files of io/ share (private). */
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <cstdint>
#include <string>
#include <sys/types.h>

namespace pcl {
namespace phaser {
namespace detail {

/** \brief Store \a message in \a error when it is not null. \return false */
bool fail(std::string* error, const std::string& message);

/** \brief The path in single quotes, the way every message names a file. */
std::string quoted(const std::string& path);

/** \brief At most \a size characters of \a text, the non-printable ones as '?'. */
std::string printable(const std::string& text, std::size_t size);

/** \brief The message for a file name that is not .pcd, .ply or .bin. */
std::string unsupportedExtension(const std::string& path);

/** \brief Whether \a path is a readable, non-empty regular file; its size in \a size.
 */
bool checkInputFile(const std::string& path, std::uintmax_t& size, std::string* error);

/** \brief The value of PCL datatype \a datatype at \a p (0 for an unknown type). */
double fieldValue(const std::uint8_t* p, std::uint8_t datatype);

/** \brief Check the blob invariants of loadCloud() and the x/y/z fields; set row_step
 * and recompute is_dense (PCL's PLY reader calls range-grid clouds with holes dense).
 */
bool checkCloudLayout(pcl::PCLPointCloud2& cloud, const std::string& path,
                      std::string* error);

/** \brief \a prefix, then a consistent cloud as a binary PCD file. */
std::string binaryPcd(const pcl::PCLPointCloud2& cloud, const std::string& prefix);

/** \brief Read a .pcd or .ply file with PCL's reader in a forked child. \return '1'
 * and the cloud as a binary PCD file, or '0' and a reason that names the file */
std::string readInChild(const std::string& path);

/** \brief The cloud of a readInChild() reply, checked as loadCloud() promises. */
bool takeReply(const std::string& path, const std::string& reply,
               pcl::PCLPointCloud2& cloud, std::string* error);

/** \brief readInChild() in the reader process of startCloudReader(). \return false
 * when none runs or it stopped answering (it is then let go) */
bool readThroughReader(const std::string& path, std::string& reply);

/** \brief fork() after flushing stdio; the child keeps only stdio and \a fd open. */
pid_t forkKeeping(int fd);

/** \brief Send \a bytes on a socket after their length (u64). */
bool sendFramed(int fd, const std::string& bytes);

/** \brief Read what sendFramed() sent. \return false at the end of the stream */
bool readFramed(int fd, std::string& bytes);

} // namespace detail
} // namespace phaser
} // namespace pcl
