"""dancers"""
